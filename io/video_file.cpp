// write_video and count_video_frames: see video_file.hpp.
#include "io/video_file.hpp"

#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace wisp::io {
namespace {

// imread of a missing file logs a warning before failing: check first, fail quietly.
cv::Mat read_image(const std::filesystem::path& frame) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(frame, ec)) return {};
  return cv::imread(frame.string(), cv::IMREAD_COLOR);
}

cv::Mat read_frame(const std::filesystem::path& video, const std::filesystem::path& frame,
                   const cv::Size& size) {
  cv::Mat image = read_image(frame);
  if (image.empty())
    throw std::runtime_error(video.string() + ": cannot read the frame " + frame.string());
  if (image.size() != size)
    throw std::runtime_error(video.string() + ": the frame " + frame.string() + " is " +
                             std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                             ", the first frame " + std::to_string(size.width) + "x" +
                             std::to_string(size.height));
  return image;
}

// Encodes every frame into `tmp` with `fourcc`; true if the result decodes to every frame.
bool encode(const std::filesystem::path& video, const std::filesystem::path& tmp,
            const std::vector<std::filesystem::path>& frames, double fps, const char* fourcc,
            const cv::Size& size) {
  {
    cv::VideoWriter writer;
    if (!writer.open(tmp.string(), cv::CAP_FFMPEG,
                     cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]), fps, size,
                     true))
      return false;
    for (const auto& f : frames) writer.write(read_frame(video, f, size));
    writer.release();
  }
  return count_video_frames(tmp) == static_cast<int>(frames.size());
}

}  // namespace

std::string write_video(const std::filesystem::path& path,
                        const std::vector<std::filesystem::path>& frames, double fps) {
  if (path.extension() != ".mp4")
    throw std::runtime_error(path.string() + ": the video must be a .mp4 file");
  if (frames.empty()) throw std::runtime_error(path.string() + ": no frames to write");
  if (!(fps > 0 && fps <= 1000))
    throw std::runtime_error(path.string() + ": fps must be in (0, 1000]");
  const cv::Mat first = read_image(frames.front());
  if (first.empty())
    throw std::runtime_error(path.string() + ": cannot read the frame " + frames.front().string());
  const cv::Size size = first.size();
  std::string used;
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    for (const char* fourcc : {"avc1", "mp4v"})
      if (encode(path, tmp, frames, fps, fourcc, size)) {
        used = fourcc;
        return;
      }
    throw std::runtime_error(path.string() +
                             ": OpenCV could not write a decodable MP4 (tried avc1 and mp4v)");
  });
  return used;
}

void check_video(const std::filesystem::path& path, int width, int height, double fps) {
  if (!(fps > 0 && fps <= 1000))
    throw std::runtime_error(path.string() + ": fps must be in (0, 1000]");
  namespace fs = std::filesystem;
  const fs::path probe =
      fs::temp_directory_path() / ("wisp-video-probe-" + std::to_string(getpid()) + ".mp4");
  const cv::Mat blank(height, width, CV_8UC3, cv::Scalar::all(0));
  bool ok = false;
  for (const char* fourcc : {"avc1", "mp4v"}) {
    {
      cv::VideoWriter writer;
      if (writer.open(probe.string(), cv::CAP_FFMPEG,
                      cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]), fps,
                      blank.size(), true))
        writer.write(blank);
    }
    ok = count_video_frames(probe) == 1;
    std::error_code ec;
    fs::remove(probe, ec);
    if (ok) return;
  }
  throw std::runtime_error(path.string() + ": cannot encode a " + std::to_string(width) + "x" +
                           std::to_string(height) +
                           " video (tried avc1 and mp4v); choose another size, or set "
                           "render.video to false");
}

int count_video_frames(const std::filesystem::path& path) {
  cv::VideoCapture capture(path.string(), cv::CAP_FFMPEG);
  if (!capture.isOpened()) return -1;
  int count = 0;
  cv::Mat frame;
  while (capture.read(frame)) ++count;
  return count;
}

}  // namespace wisp::io
