// Toon ramp bands and lookups (see toon_ramp.hpp).
#include "vector/toon_ramp.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::vector {

RampBands::RampBands(const ToonRamp& ramp, double jump_threshold) : ramp_(ramp) {
  for (int c = 1; c < ramp.width; ++c) {
    float jump = 0;
    for (int r = 0; r < ramp.height; ++r)
      jump = std::max(jump, (ramp.at(c, r) - ramp.at(c - 1, r)).cwiseAbs().maxCoeff());
    if (jump > jump_threshold) {
      edge_col_.push_back(c);
      edge_x_.push_back(double(c) / ramp.width);
    }
  }
}

int RampBands::band(double x) const {
  return int(std::upper_bound(edge_x_.begin(), edge_x_.end(), x) - edge_x_.begin());
}

Eigen::Vector3f RampBands::lookup(double x, double y, int band) const {
  const ToonRamp& r = ramp_;
  if (r.width <= 0 || r.height <= 0) return Eigen::Vector3f::Zero();
  band = std::clamp(band, 0, int(edge_col_.size()));
  const int c0 = band == 0 ? 0 : edge_col_[band - 1];
  const int c1 = band == int(edge_col_.size()) ? r.width - 1 : edge_col_[band] - 1;
  // Pixel centres sit at (i + 0.5) / size.
  const double cx = std::clamp(std::clamp(x, 0.0, 1.0) * r.width - 0.5, double(c0), double(c1));
  const double cy = std::clamp(std::clamp(y, 0.0, 1.0) * r.height - 0.5, 0.0, r.height - 1.0);
  const int x0 = int(std::floor(cx)), y0 = int(std::floor(cy));
  const int x1 = std::min(x0 + 1, c1), y1 = std::min(y0 + 1, r.height - 1);
  const float fx = float(cx - x0), fy = float(cy - y0);
  const Eigen::Vector3f top = (1 - fx) * r.at(x0, y0) + fx * r.at(x1, y0);
  const Eigen::Vector3f bottom = (1 - fx) * r.at(x0, y1) + fx * r.at(x1, y1);
  return (1 - fy) * top + fy * bottom;
}

}  // namespace wisp::vector
