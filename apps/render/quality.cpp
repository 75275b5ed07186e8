// frame_quality (see quality.hpp): box filter by OpenCV's area resampling, which for an integer
// factor is exactly the block mean.
#include "apps/render/quality.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace wisp::render {
namespace {

cv::Mat read_rgb(const std::filesystem::path& path) {
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (m.empty()) throw std::runtime_error(path.string() + ": cannot read the image");
  m.convertTo(m, CV_32FC3);
  return m;
}

// The largest per-channel difference of two colours (0-255).
float colour_distance(const cv::Vec3f& p, const cv::Vec3f& q) {
  return std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])});
}

}  // namespace

FrameQuality frame_quality(const std::filesystem::path& frame,
                           const std::filesystem::path& reference,
                           const Eigen::Vector3f& background) {
  const cv::Mat a = read_rgb(frame), big = read_rgb(reference);
  if (big.cols % a.cols != 0 || big.rows % a.rows != 0 || big.cols / a.cols != big.rows / a.rows)
    throw std::runtime_error(reference.string() + ": size " + std::to_string(big.cols) + "x" +
                             std::to_string(big.rows) + " is not a multiple of " + frame.string() +
                             "'s");
  cv::Mat b;
  cv::resize(big, b, a.size(), 0, 0, cv::INTER_AREA);
  const cv::Vec3f bg(background[2] * 255, background[1] * 255, background[0] * 255);  // BGR
  const auto off_background = [&](const cv::Vec3f& p) { return colour_distance(p, bg) > 3; };
  std::vector<float> errors;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) {
      const cv::Vec3f p = a.at<cv::Vec3f>(y, x), q = b.at<cv::Vec3f>(y, x);
      if (!off_background(p) && !off_background(q)) continue;
      errors.push_back(colour_distance(p, q));
    }
  FrameQuality out;
  out.figure_pixels = long(errors.size());
  if (errors.empty()) return out;
  double sum = 0;
  long over = 0;
  for (float e : errors) sum += e, over += e > 32;
  out.mean = sum / errors.size();
  out.over_32 = double(over) / errors.size();
  const size_t k = std::min(errors.size() - 1, size_t(std::ceil(0.99 * errors.size())) - 1);
  std::nth_element(errors.begin(), errors.begin() + k, errors.end());
  out.p99 = errors[k];
  return out;
}

}  // namespace wisp::render
