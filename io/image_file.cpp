// PNG output through OpenCV (see image_file.hpp).
#include "io/image_file.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace wisp::io {

void write_png(const std::filesystem::path& path, const diffusion::Image& image) {
  if (path.extension() != ".png")
    throw std::runtime_error(path.string() + ": the output must be a .png file");
  const size_t n = size_t(image.width) * size_t(image.height);
  cv::Mat bgr(image.height, image.width, CV_8UC3);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = std::clamp(image.planes[c * n + i], 0.0f, 1.0f);
      bgr.data[3 * i + (2 - c)] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    if (!cv::imwrite(tmp.string(), bgr))
      throw std::runtime_error(path.string() + ": cannot write the PNG file");
  });
}

}  // namespace wisp::io
