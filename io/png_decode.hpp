// PNG decoding with libpng into 8-bit RGB rows: ramps, and the frames that the contact sheet and
// the preview video are made of. The conversions are those of OpenCV's imread(IMREAD_COLOR),
// which read these files before, so the pixels are the same: 16-bit samples keep their high byte,
// alpha and tRNS are dropped (not composited), palettes and grey levels expand to RGB, interlaced
// images are de-interlaced; no gamma or colour-profile conversion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wisp::io {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, 3 bytes (R, G, B) per pixel, no padding
};

// Decodes a whole PNG file held in memory. Images with a side above `max_side` are refused before
// their pixels are decoded. Throws std::runtime_error saying what is wrong (no file name).
RgbImage decode_png(const std::uint8_t* data, std::size_t size, int max_side);

// Reads and decodes the PNG file `path`; `what` names it in errors ("frame"). Throws
// std::runtime_error "<path>: ...".
RgbImage read_png(const std::filesystem::path& path, const std::string& what, int max_side);

}  // namespace wisp::io
