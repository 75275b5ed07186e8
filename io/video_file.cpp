// write_video, VideoCheck, check_video and count_video_frames (see video_file.hpp): the frames are
// read here (io/png_decode) and handed to the video module (io/video_module.hpp), loaded on first
// use.
#include "io/video_file.hpp"

#include <dlfcn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
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
  const fs::path probe =
      fs::temp_directory_path() / ("wisp-video-probe-" + std::to_string(getpid()) + ".mp4");
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

VideoCheck::VideoCheck(const std::filesystem::path& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  if (!(fps > 0 && fps <= 1000))
    throw std::runtime_error(path.string() + ": fps must be in (0, 1000]");
  // The probe runs in a child process: once loaded, the video module (FFmpeg, x264) stays
  // resident, about 60 MB, and a render needs it only for its last step. The child reports an
  // error as one byte, 'M' (VideoModuleError) or 'E', then the message.
  int fds[2];
  const pid_t child = pipe(fds) == 0 ? fork() : -2;
  if (child < 0) {  // no pipe or no fork: probe here, at the cost of the memory
    if (child == -1) {
      close(fds[0]);
      close(fds[1]);
    }
    try {
      probe_video(path, width, height, fps);
    } catch (...) {
      error_ = std::current_exception();
    }
    return;
  }
  if (child == 0) {
    close(fds[0]);
    std::string report;
    try {
      probe_video(path, width, height, fps);
    } catch (const VideoModuleError& e) {
      report = std::string("M") + e.what();
    } catch (const std::exception& e) {
      report = std::string("E") + e.what();
    }
    for (std::size_t at = 0; at < report.size();) {
      const ssize_t n = write(fds[1], report.data() + at, report.size() - at);
      if (n <= 0) break;
      at += std::size_t(n);
    }
    _exit(0);  // no atexit handlers or static destructors of the parent's state
  }
  close(fds[1]);
  child_ = child;
  report_ = fds[0];
}

VideoCheck::~VideoCheck() {
  std::lock_guard<std::mutex> lock(mutex_);
  collect();
}

void VideoCheck::wait() {
  std::lock_guard<std::mutex> lock(mutex_);
  collect();
  if (error_) std::rethrow_exception(error_);
}

void VideoCheck::collect() {
  if (child_ < 0) return;
  std::string report;
  char buf[512];
  for (ssize_t n; (n = read(report_, buf, sizeof buf)) != 0;) {
    if (n > 0)
      report.append(buf, std::size_t(n));
    else if (errno != EINTR)
      break;
  }
  close(report_);
  int status = 0;
  while (waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = -1;
  if (!WIFEXITED(status))
    error_ = std::make_exception_ptr(
        std::runtime_error(path_.string() + ": the video probe for a " + std::to_string(width_) +
                           "x" + std::to_string(height_) + " video crashed"));
  else if (!report.empty() && report[0] == 'M')
    error_ = std::make_exception_ptr(VideoModuleError(report.substr(1)));
  else if (!report.empty())
    error_ = std::make_exception_ptr(std::runtime_error(report.substr(1)));
}

void check_video(const std::filesystem::path& path, int width, int height, double fps) {
  VideoCheck(path, width, height, fps).wait();
}

int count_video_frames(const std::filesystem::path& path) {
  return video_module(path).count_frames(path.c_str());
}

}  // namespace wisp::io
