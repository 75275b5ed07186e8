// A test helper that allocates with glibc's malloc, not the project's jemalloc: writes ten 96x64
// frames through the video module's C functions (io/video_module.hpp), so that MALLOC_PERTURB_
// decides what the memory handed to the encoder holds before it writes it. Used by the test "a
// video's bytes do not depend on what the heap held before" (tests/io/test_video_file.cpp).
// Usage: video_heap_writer MODULE OUT.mp4; exit code 0 when the video was written.
#include <dlfcn.h>

#include <vector>

#include "io/video_module.hpp"

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  void* module = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (!module) return 3;
  const auto open = reinterpret_cast<decltype(&wisp_video_open)>(dlsym(module, "wisp_video_open"));
  const auto write =
      reinterpret_cast<decltype(&wisp_video_write)>(dlsym(module, "wisp_video_write"));
  const auto close =
      reinterpret_cast<decltype(&wisp_video_close)>(dlsym(module, "wisp_video_close"));
  if (!open || !write || !close) return 3;
  // A disc moving across a gradient: B frames, and a width of 6 macroblocks (not a multiple of 8).
  constexpr int kWidth = 96, kHeight = 64, kFrames = 10;
  std::vector<unsigned char> rgb(kWidth * kHeight * 3);
  void* video = open(argv[2], "avc1", 24, kWidth, kHeight);
  if (!video) return 4;
  for (int i = 0; i < kFrames; ++i) {
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const int dx = x - (8 + i * 8), dy = y - kHeight / 2;
        const bool disc = dx * dx + dy * dy < 100;
        unsigned char* p = &rgb[3 * (y * kWidth + x)];
        p[0] = disc ? 240 : 90;
        p[1] = disc ? 40 : (unsigned char)(y * 255 / kHeight);
        p[2] = disc ? 20 : (unsigned char)(x * 255 / kWidth);
      }
    if (!write(video, rgb.data())) return 5;
  }
  close(video);
  return 0;
}
