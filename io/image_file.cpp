// PNG output of float planes through the frames' encoder, io/png_encode (see image_file.hpp).
#include "io/image_file.hpp"

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "io/png_encode.hpp"

namespace wisp::io {

void write_png(const std::filesystem::path& path, const diffusion::Image& image) {
  if (path.extension() != ".png")
    throw std::runtime_error(path.string() + ": the output must be a .png file");
  std::vector<std::uint32_t> words(size_t(image.width) * size_t(image.height));  // as RGB
  pack_rgb_box(image, 0, 0, image.width, image.height, words.data(), size_t(image.width));
  write_png_fast(path, {reinterpret_cast<const std::uint8_t*>(words.data()), image.width,
                        image.height, 3, size_t(image.width) * 4, true});
}

void pack_rgb_box(const diffusion::Image& image, int x0, int y0, int x1, int y1, std::uint32_t* out,
                  std::size_t stride) {
  const size_t n = size_t(image.width) * size_t(image.height);
  for (int y = y0; y < y1; ++y) {
    const float* r = &image.planes[size_t(y) * image.width + x0];
    pack_rgb(r, r + n, r + 2 * n, out + size_t(y - y0) * stride, x1 - x0);
  }
}

}  // namespace wisp::io
