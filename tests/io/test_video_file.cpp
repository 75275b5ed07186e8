// The MP4 preview: frame count after decoding, determinism, atomic writing, errors.

#include <unistd.h>
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "io/png_decode.hpp"
#include "io/video_file.hpp"
#include "tests/test_folder.hpp"

namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
  return wisp::test::test_folder("video_file");
}

// `count` frames of a disc moving across a gradient, as PNG files.
std::vector<fs::path> synthetic_frames(const fs::path& dir, int count, int w, int h) {
  std::vector<fs::path> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat m(h, w, CV_8UC3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(x * 255 / w, y * 255 / h, 90);
    cv::circle(m, cv::Point(8 + i * (w - 16) / std::max(1, count - 1), h / 2), h / 6,
               cv::Scalar(20, 40, 240), cv::FILLED, cv::LINE_AA);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", i);
    frames.push_back(dir / name);
    REQUIRE(cv::imwrite(frames.back().string(), m));
  }
  return frames;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("a 10-frame synthetic video decodes to 10 frames, the same bytes twice", "[io][video]") {
  const fs::path dir = temp_dir();
  const std::vector<fs::path> frames = synthetic_frames(dir, 10, 96, 64);
  const fs::path video = dir / "preview.mp4";
  const std::string fourcc = wisp::io::write_video(video, frames, 24);
  INFO("fourcc " << fourcc);
  CHECK((fourcc == "avc1" || fourcc == "mp4v"));
  CHECK(wisp::io::count_video_frames(video) == 10);
  // The decoded frames are the right size and look like the inputs (lossy, so roughly).
  cv::VideoCapture capture(video.string());
  cv::Mat decoded;
  REQUIRE(capture.read(decoded));
  CHECK(decoded.cols == 96);
  CHECK(decoded.rows == 64);
  const cv::Mat first = cv::imread(frames[0].string());
  CHECK(cv::norm(decoded, first, cv::NORM_L1) / first.total() / 3 < 6.0);
  // Deterministic, and nothing but the video is left in the folder. A reader of the same frames
  // is shown each of them once, in order, and the video's bytes do not change.
  const std::string once = bytes(video);
  std::vector<int> shown;
  wisp::io::write_video(video, frames, 24, [&](int i, const wisp::io::RgbImage& frame) {
    shown.push_back(i);
    CHECK(frame.width == 96);
    CHECK(frame.pixels == wisp::io::read_png(frames[size_t(i)], "frame", 4096).pixels);
  });
  CHECK(shown == std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK(bytes(video) == once);
  int partial = 0;
  for (const auto& e : fs::directory_iterator(dir))
    partial += e.path().filename().string().find("partial") != std::string::npos;
  CHECK(partial == 0);
  // Odd sizes work too (4:2:0 needs even sides: the last column and row are dropped).
  const fs::path odd_dir = dir / "odd";
  fs::create_directories(odd_dir);
  CHECK(wisp::io::write_video(odd_dir / "odd.mp4", synthetic_frames(odd_dir, 3, 33, 21), 12) != "");
  CHECK(wisp::io::count_video_frames(odd_dir / "odd.mp4") == 3);
  fs::remove_all(dir);
}

TEST_CASE("a video's bytes do not depend on what the heap held before", "[io][video]") {
  // x264's AVX-512 code read memory it had never written (io/video_module.cpp), which showed only
  // when other test cases had run before in the same process. A helper allocating with glibc's
  // malloc writes the same video with new memory zeroed and filled with two other bytes.
  const fs::path dir = temp_dir();
  std::string zeroed;
  for (const int perturb : {0, 1, 165}) {
    const fs::path video = dir / ("heap" + std::to_string(perturb) + ".mp4");
    const std::string command = "MALLOC_PERTURB_=" + std::to_string(perturb) +
                                " " WISP_BIN_DIR "/video_heap_writer " WISP_BIN_DIR
                                "/../lib/wisp/wisp-video.so " +
                                video.string();
    INFO(command);
    REQUIRE(std::system(command.c_str()) == 0);
    if (perturb == 0)
      zeroed = bytes(video);
    else
      CHECK(bytes(video) == zeroed);
  }
  CHECK(!zeroed.empty());
  fs::remove_all(dir);
}

TEST_CASE("video errors name the file and leave nothing behind", "[io][video]") {
  const fs::path dir = temp_dir();
  const std::vector<fs::path> frames = synthetic_frames(dir, 2, 32, 32);
  CHECK_THROWS_WITH(wisp::io::write_video(dir / "v.avi", frames, 24), Catch::Contains(".mp4"));
  CHECK_THROWS_WITH(wisp::io::write_video(dir / "v.mp4", {}, 24), Catch::Contains("no frames"));
  CHECK_THROWS_WITH(wisp::io::write_video(dir / "v.mp4", frames, 0), Catch::Contains("fps"));
  CHECK_THROWS_WITH(wisp::io::write_video(dir / "v.mp4", {frames[0], dir / "missing.png"}, 24),
                    Catch::Contains("missing.png"));
  fs::create_directories(dir / "big");
  const std::vector<fs::path> big = synthetic_frames(dir / "big", 1, 48, 32);
  CHECK_THROWS_WITH(wisp::io::write_video(dir / "v.mp4", {frames[0], big[0]}, 24),
                    Catch::Contains("48x32"));
  CHECK_THROWS_WITH(wisp::io::write_video(dir / "nope" / "v.mp4", frames, 24),
                    Catch::Contains("does not exist"));
  CHECK(!fs::exists(dir / "v.mp4"));
  int partial = 0;
  for (const auto& e : fs::directory_iterator(dir))
    partial += e.path().filename().string().find("partial") != std::string::npos;
  CHECK(partial == 0);
  CHECK(wisp::io::count_video_frames(dir / "missing.mp4") == -1);
  fs::remove_all(dir);
}

// The probe files this process left in the temporary folder.
int probe_files_left() {
  const std::string prefix = "wisp-video-probe-" + std::to_string(getpid()) + "-";
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    n += e.path().filename().string().rfind(prefix, 0) == 0;
  return n;
}

TEST_CASE("the video check probes beside the caller and reports its answer", "[io][video]") {
  const fs::path dir = temp_dir();
  CHECK_NOTHROW(wisp::io::check_video(dir / "v.mp4", 64, 48, 24));
  // A size no codec takes: the probe's error comes back to the caller, naming the video.
  CHECK_THROWS_WITH(wisp::io::check_video(dir / "v.mp4", 0, 0, 24),
                    Catch::Contains("v.mp4") && Catch::Contains("cannot encode a 0x0 video"));
  CHECK_THROWS_WITH(wisp::io::check_video(dir / "v.mp4", 64, 48, 0), Catch::Contains("fps"));
  // Two at once, each with a probe file of its own; an answer is kept for every later wait.
  wisp::io::VideoCheck good(dir / "a.mp4", 64, 48, 24), bad(dir / "b.mp4", 0, 0, 24);
  CHECK_THROWS_WITH(bad.wait(), Catch::Contains("b.mp4"));
  CHECK_THROWS_WITH(bad.wait(), Catch::Contains("b.mp4"));
  CHECK_NOTHROW(good.wait());
  CHECK(probe_files_left() == 0);
  CHECK(!fs::exists(dir / "v.mp4"));
  fs::remove_all(dir);
}
