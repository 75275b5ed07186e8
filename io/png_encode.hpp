// Fast PNG encoding for the frames of a render: libpng at zlib level 1 with the Up filter only and
// run-length matches (Z_RLE).
// Frames are mostly smooth gradients and flat fills, where that costs about a tenth of the time
// of the default (level 6, adaptive filters) for files a few per cent larger; the pixels are the
// same. Writing is on the per-frame path (the frame and the hair image inside its SVG), so it is
// worth a dedicated encoder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace wisp::io {

// 8-bit pixels, row-major, `channels` bytes per pixel (1 grey, 3 RGB, 4 RGBA), `stride` bytes
// from one row to the next. With `xrgb32` and 3 channels, each pixel is instead a native-endian
// 32-bit word 0xXXRRGGBB (Cairo's RGB24), written as RGB without a copy of the image.
struct PixelRows {
  const std::uint8_t* data = nullptr;
  int width = 0, height = 0, channels = 3;
  std::size_t stride = 0;
  bool xrgb32 = false;
};

// A colour channel in [0,1] (clamped; NaN as 0) as a byte: std::lround(v * 255) exactly (halves
// away from zero), without the library call.
inline std::uint8_t unit_byte(float v) {
  const float x = (v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f) * 255.0f;
  const int i = int(x);
  return std::uint8_t(i + (x - float(i) >= 0.5f ? 1 : 0));  // x - i is exact for x in [0, 255]
}

// n opaque pixels 0xffRRGGBB (Cairo's RGB24 and ARGB32 words; PixelRows::xrgb32) from three
// planes of channels in [0,1], each byte unit_byte of its channel (vectorised where the CPU has
// SSE2).
void pack_rgb(const float* r, const float* g, const float* b, std::uint32_t* out, int n);

// The PNG file's bytes. Throws std::runtime_error when libpng fails.
std::vector<std::uint8_t> encode_png(const PixelRows& pixels);

// Encodes and writes atomically (io/atomic_file.hpp). Throws std::runtime_error naming the file.
void write_png_fast(const std::filesystem::path& path, const PixelRows& pixels);

}  // namespace wisp::io
