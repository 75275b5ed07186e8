// Reading toon ramps (see ramp_file.hpp).
#include "io/ramp_file.hpp"

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace wisp::io {

std::shared_ptr<const vector::ToonRamp> read_ramp(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error(path.string() + ": no such ramp image");
  const cv::Mat img = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (img.empty() || img.cols <= 0 || img.rows <= 0)
    throw std::runtime_error(path.string() +
                             ": not a readable image, or an image of 0 pixels (a ramp needs at "
                             "least one)");
  auto ramp = std::make_shared<vector::ToonRamp>();
  ramp->width = img.cols;
  ramp->height = img.rows;
  ramp->source = path.string();
  ramp->pixels.reserve(size_t(img.cols) * img.rows);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b& bgr = img.at<cv::Vec3b>(y, x);
      ramp->pixels.emplace_back(bgr[2] / 255.0f, bgr[1] / 255.0f, bgr[0] / 255.0f);
    }
  return ramp;
}

}  // namespace wisp::io
