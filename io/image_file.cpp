// PNG output of float planes through the frames' encoder, io/png_encode (see image_file.hpp).
#include "io/image_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "io/png_encode.hpp"

namespace wisp::io {

void write_png(const std::filesystem::path& path, const diffusion::Image& image) {
  if (path.extension() != ".png")
    throw std::runtime_error(path.string() + ": the output must be a .png file");
  const size_t n = size_t(image.width) * size_t(image.height);
  std::vector<std::uint8_t> rgb(3 * n);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = std::clamp(image.planes[c * n + i], 0.0f, 1.0f);
      rgb[3 * i + c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  write_png_fast(path, {rgb.data(), image.width, image.height, 3, size_t(image.width) * 3});
}

}  // namespace wisp::io
