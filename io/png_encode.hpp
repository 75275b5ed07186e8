// Fast PNG encoding for the frames of a render: the Up filter on every row, compressed by ISA-L's
// igzip at its level 1 (Intel's SIMD deflate, Debian's libisal), the PNG chunks around it written
// here (libpng cannot take another deflate). Frames are mostly smooth gradients and flat fills:
// a 1024^2 frame compresses in about a fifth of the time of zlib's level 1 with run-length
// matches, which wisp used before, for 3-4 % more bytes (docs/performance.md, "Writing with
// igzip"); the pixels are the same. Writing is on the per-frame path (the frame, the hair image
// inside its SVG, the mask), so it is worth a dedicated encoder. PNGs are read with libpng
// (png_decode.hpp). An image of more than a megabyte is compressed in parts by the worker threads
// (png_encode.cpp, compressed_rows), the same bytes at any thread count.
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
// SSE2 or AVX-512).
void pack_rgb(const float* r, const float* g, const float* b, std::uint32_t* out, int n);

// The PNG file's bytes. Throws std::runtime_error for a bad layout or when compression fails.
std::vector<std::uint8_t> encode_png(const PixelRows& pixels);

// Encodes and writes atomically (io/atomic_file.hpp). Throws std::runtime_error naming the file.
void write_png_fast(const std::filesystem::path& path, const PixelRows& pixels);

}  // namespace wisp::io
