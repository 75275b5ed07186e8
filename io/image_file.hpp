// Image files: float RGB planes (diffusion::Image) to 8-bit PNG, written atomically.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "diffusion/render.hpp"

namespace wisp::io {

// Values are clamped to [0,1] and rounded to 8 bits. Throws std::runtime_error naming the file.
void write_png(const std::filesystem::path& path, const diffusion::Image& image);

// The box [x0, x1) x [y0, y1) of the image as opaque 0xffRRGGBB words (io::pack_rgb), row y0 at
// `out`, each next row `stride` words further (Cairo's image surfaces, PixelRows::xrgb32).
void pack_rgb_box(const diffusion::Image& image, int x0, int y0, int x1, int y1, std::uint32_t* out,
                  std::size_t stride);

}  // namespace wisp::io
