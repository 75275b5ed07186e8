// Image files: float RGB planes (diffusion::Image) to 8-bit PNG, written atomically.
#pragma once

#include <filesystem>

#include "diffusion/render.hpp"

namespace wisp::io {

// Values are clamped to [0,1] and rounded to 8 bits. Throws std::runtime_error naming the file.
void write_png(const std::filesystem::path& path, const diffusion::Image& image);

}  // namespace wisp::io
