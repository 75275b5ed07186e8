// The MP4 preview: PNG frames, in order, through FFmpeg, which lives in the video module loaded on
// first use (io/video_module.hpp). H.264 (fourcc "avc1", x264) is tried first, MPEG-4 part 2
// ("mp4v") if that fails; a codec counts as working only when the finished file decodes back to
// every frame. The file is written atomically (io/atomic_file.hpp): the temporary keeps the .mp4
// extension. Same frames, same bytes, whatever the process did before (video_module.cpp says
// which encoder settings that takes).
#pragma once

#include <exception>
#include <filesystem>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "io/png_decode.hpp"

namespace wisp::io {

// Thrown by every function below when the video module (io/video_module.hpp) cannot be loaded: an
// incomplete build or installation, not a fault of the input. The message names the module.
struct VideoModuleError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes `frames` (PNG files, all of the same size) at `fps` frames per second.
// Returns the fourcc that worked ("avc1" or "mp4v"). Throws std::runtime_error naming the file:
// no frames, a frame that cannot be read or differs in size, a path not ending in .mp4, fps not
// in (0, 1000], or no codec that writes a decodable file. `each_frame` (optional) is shown every
// frame once, in order, with its index, as it is read: another writer of the same frames (the
// contact sheet) need not read them again.
std::string write_video(const std::filesystem::path& path,
                        const std::vector<std::filesystem::path>& frames, double fps,
                        const std::function<void(int, const RgbImage&)>& each_frame = {});

// Checks, before any frame is written, that a width x height video at `fps` can be written:
// encodes one blank frame to a temporary file outside the output folder and reads it back, on a
// thread of its own beside the caller, which asks for its answer only when it needs it: `wisp
// render` starts the check before the first frame and awaits it before writing that frame, so
// the probe is not added to the first frame's latency. The module it loads is the one
// write_video uses later (loaded once per process). A child process kept the module out of the
// caller, but copying the caller's pages on write cost the frames more CPU than the probe itself
// (docs/performance.md, "The tenth session").
class VideoCheck {
 public:
  // Starts the probe. Throws at once what needs no probe (fps not in (0, 1000]).
  VideoCheck(const std::filesystem::path& path, int width, int height, double fps);
  // Waits for the probe when wait() was not called: no thread or probe file is left behind.
  ~VideoCheck();
  VideoCheck(const VideoCheck&) = delete;
  VideoCheck& operator=(const VideoCheck&) = delete;

  // Blocks until the answer. Throws std::runtime_error "<path>: ..." when the video cannot be
  // written (sizes the codecs refuse), VideoModuleError when the module is missing; every later
  // call returns or throws the same at once. Safe to call from any thread.
  void wait();

 private:
  std::mutex mutex_;          // held by wait() and the destructor while they join
  std::exception_ptr error_;  // written by the probe's thread, read after joining it
  std::thread probe_;
};

// The same, waited for: VideoCheck(path, width, height, fps).wait().
void check_video(const std::filesystem::path& path, int width, int height, double fps);

// Decodes the whole video and counts its frames; -1 if it cannot be opened.
int count_video_frames(const std::filesystem::path& path);

}  // namespace wisp::io
