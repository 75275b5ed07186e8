// Toon ramp images (vector/toon_ramp.hpp) read from PNG files as RGB in
// [0, 1], used as given, like every colour of a scene.
#pragma once

#include <filesystem>
#include <memory>

#include "vector/toon_ramp.hpp"

namespace wisp::io {

// The largest side of a ramp image, in pixels (ramps are a few dozen).
constexpr int kMaxRampSide = 4096;

// Throws std::runtime_error naming the file when it cannot be read as an image or has no pixels.
std::shared_ptr<const vector::ToonRamp> read_ramp(const std::filesystem::path& path);

}  // namespace wisp::io
