// Measures of frames shared by end-to-end tests (see image_checks.hpp).
#include "image_checks.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

namespace wisp::test {

double mask_iou(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat both, either;
  cv::bitwise_and(a, b, both);
  cv::bitwise_or(a, b, either);
  const double u = cv::countNonZero(either);
  return u > 0 ? cv::countNonZero(both) / u : 1.0;
}

double distance_to_rings(const std::vector<std::vector<Eigen::Vector2d>>& rings,
                         const Eigen::Vector2d& p) {
  double best = INFINITY;
  for (const auto& r : rings)
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const Eigen::Vector2d a = r[j], d = r[i] - r[j];
      const double f = std::clamp((p - a).dot(d) / std::max(1e-12, d.squaredNorm()), 0.0, 1.0);
      best = std::min(best, (a + f * d - p).norm());
    }
  return best;
}

}  // namespace wisp::test
