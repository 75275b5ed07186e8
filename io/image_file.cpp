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
  const size_t n = size_t(image.width) * size_t(image.height);
  std::vector<std::uint32_t> words(n);  // 0xffRRGGBB, encoded as RGB
  for (int y = 0; y < image.height; ++y) {
    const float* r = &image.planes[size_t(y) * image.width];
    pack_rgb(r, r + n, r + 2 * n, &words[size_t(y) * image.width], image.width);
  }
  write_png_fast(path, {reinterpret_cast<const std::uint8_t*>(words.data()), image.width,
                        image.height, 3, size_t(image.width) * 4, true});
}

}  // namespace wisp::io
