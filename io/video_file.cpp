// write_video, VideoCheck, check_video and count_video_frames (see video_file.hpp): the frames are
// read here (io/png_decode) and handed to the video module (io/video_module.hpp), loaded on first
// use.
#include "io/video_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/drawing_xml.hpp"
#include "io/png_decode.hpp"
#include "io/video_module.hpp"
#include "util/module.hpp"

namespace wisp::io {
namespace {

struct VideoModule {
  decltype(&wisp_video_open) open = nullptr;
  decltype(&wisp_video_write) write = nullptr;
  decltype(&wisp_video_close) close = nullptr;
  decltype(&wisp_video_count_frames) count_frames = nullptr;
  std::string error;  // why it could not be loaded; empty when it was
};

// Loaded once per process (util/module.hpp). Throws "<video>: ..." when the module is missing.
const VideoModule& video_module(const std::filesystem::path& video) {
  static const VideoModule loaded = [] {
    util::Module module = util::open_module("wisp-video.so", "video");
    VideoModule m;
    m.open = module.function<decltype(m.open)>("wisp_video_open");
    m.write = module.function<decltype(m.write)>("wisp_video_write");
    m.close = module.function<decltype(m.close)>("wisp_video_close");
    m.count_frames = module.function<decltype(m.count_frames)>("wisp_video_count_frames");
    m.error = module.error;
    return m;
  }();
  if (!loaded.error.empty()) throw VideoModuleError(video.string() + ": " + loaded.error);
  return loaded;
}

// The frame's pixels, or an error naming the video and the frame.
RgbImage read_frame(const std::filesystem::path& video, const std::filesystem::path& frame) {
  try {
    return read_png(frame, "frame", kMaxImageSide);
  } catch (const std::runtime_error&) {
    throw std::runtime_error(video.string() + ": cannot read the frame " + frame.string());
  }
}

// Encodes `count` frames, each produced by frame(i), into `tmp` with `fourcc`; true if the result
// decodes to every frame.
template <typename Frame>
bool encode(const VideoModule& m, const std::filesystem::path& tmp, int count, double fps,
            const char* fourcc, int width, int height, const Frame& frame) {
  void* writer = m.open(tmp.c_str(), fourcc, fps, width, height);
  if (!writer) return false;
  bool written = true;
  try {
    for (int i = 0; i < count && written; ++i) written = m.write(writer, frame(i)) != 0;
  } catch (...) {
    m.close(writer);
    throw;
  }
  m.close(writer);
  return written && m.count_frames(tmp.c_str()) == count;
}

}  // namespace

std::string write_video(const std::filesystem::path& path,
                        const std::vector<std::filesystem::path>& frames, double fps,
                        const std::function<void(int, const RgbImage&)>& each_frame) {
  if (path.extension() != ".mp4")
    throw std::runtime_error(path.string() + ": the video must be a .mp4 file");
  if (frames.empty()) throw std::runtime_error(path.string() + ": no frames to write");
  if (!(fps > 0 && fps <= 1000))
    throw std::runtime_error(path.string() + ": fps must be in (0, 1000]");
  const RgbImage first = read_frame(path, frames.front());
  const VideoModule& m = video_module(path);
  RgbImage current;
  int shown = 0;  // frames handed to each_frame (a second codec's attempt reads them again)
  const auto frame = [&](int i) -> const unsigned char* {
    const RgbImage* image = &first;
    if (i > 0) {
      current = read_frame(path, frames[i]);
      if (current.width != first.width || current.height != first.height)
        throw std::runtime_error(path.string() + ": the frame " + frames[i].string() + " is " +
                                 std::to_string(current.width) + "x" +
                                 std::to_string(current.height) + ", the first frame " +
                                 std::to_string(first.width) + "x" + std::to_string(first.height));
      image = &current;
    }
    if (each_frame && i == shown) each_frame(i, *image), ++shown;
    return image->pixels.data();
  };
  std::string used;
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    for (const char* fourcc : {"avc1", "mp4v"})
      if (encode(m, tmp, int(frames.size()), fps, fourcc, first.width, first.height, frame)) {
        used = fourcc;
        return;
      }
    throw std::runtime_error(path.string() +
                             ": FFmpeg could not write a decodable MP4 (tried avc1 and mp4v)");
  });
  return used;
}

namespace {

// check_video's probe, in whatever process runs it.
void probe_video(const std::filesystem::path& path, int width, int height, double fps) {
  const VideoModule& m = video_module(path);
  namespace fs = std::filesystem;
  // Probes of several threads of one process each have a file of their own.
  static std::atomic<int> probes{0};
  const fs::path probe =
      fs::temp_directory_path() /
      ("wisp-video-probe-" + std::to_string(getpid()) + "-" + std::to_string(probes++) + ".mp4");
  const std::vector<std::uint8_t> blank(std::size_t(width) * height * 3, 0);
  for (const char* fourcc : {"avc1", "mp4v"}) {
    const bool ok =
        encode(m, probe, 1, fps, fourcc, width, height, [&](int) { return blank.data(); });
    std::error_code ec;
    fs::remove(probe, ec);
    if (ok) return;
  }
  throw std::runtime_error(path.string() + ": cannot encode a " + std::to_string(width) + "x" +
                           std::to_string(height) +
                           " video (tried avc1 and mp4v); choose another size, or set "
                           "render.video to false");
}

}  // namespace

VideoCheck::VideoCheck(const std::filesystem::path& path, int width, int height, double fps) {
  if (!(fps > 0 && fps <= 1000))
    throw std::runtime_error(path.string() + ": fps must be in (0, 1000]");
  probe_ = std::thread([this, path, width, height, fps] {
    try {
      probe_video(path, width, height, fps);
    } catch (...) {
      error_ = std::current_exception();
    }
  });
}

VideoCheck::~VideoCheck() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (probe_.joinable()) probe_.join();
}

void VideoCheck::wait() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (probe_.joinable()) probe_.join();
  if (error_) std::rethrow_exception(error_);
}

void check_video(const std::filesystem::path& path, int width, int height, double fps) {
  VideoCheck(path, width, height, fps).wait();
}

int count_video_frames(const std::filesystem::path& path) {
  return video_module(path).count_frames(path.c_str());
}

}  // namespace wisp::io
