// Fast PNG encoding for the frames of a render: libpng at zlib level 1 with the Up filter only.
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
// from one row to the next.
struct PixelRows {
  const std::uint8_t* data = nullptr;
  int width = 0, height = 0, channels = 3;
  std::size_t stride = 0;
};

// The PNG file's bytes. Throws std::runtime_error when libpng fails.
std::vector<std::uint8_t> encode_png(const PixelRows& pixels);

// Encodes and writes atomically (io/atomic_file.hpp). Throws std::runtime_error naming the file.
void write_png_fast(const std::filesystem::path& path, const PixelRows& pixels);

}  // namespace wisp::io
