// The centripetal Catmull-Rom to Bezier conversion (see catmull_rom.hpp).
#include "vector/catmull_rom.hpp"

#include <cmath>

namespace wisp::vector {

using Eigen::Vector2d;

diffusion::BezierPath catmull_rom_path(const std::vector<Vector2d>& p) {
  const int n = int(p.size());
  diffusion::BezierPath path;
  if (n < 2) return path;
  // Point i with phantom reflections at both ends.
  auto at = [&](int i) -> Vector2d {
    if (i < 0) return 2 * p[0] - p[1];
    if (i >= n) return 2 * p[n - 1] - p[n - 2];
    return p[i];
  };
  // Centripetal knot interval between points i and i+1: |P_{i+1} - P_i|^(1/2).
  auto knot = [&](int i) { return std::sqrt((at(i + 1) - at(i)).norm()); };
  // Tangent at point i with respect to the knot parameter.
  auto tangent = [&](int i) -> Vector2d {
    const double d0 = knot(i - 1), d1 = knot(i);
    return (at(i) - at(i - 1)) / d0 - (at(i + 1) - at(i - 1)) / (d0 + d1) +
           (at(i + 1) - at(i)) / d1;
  };
  for (int i = 0; i + 1 < n; ++i) {
    const double d = knot(i);
    path.append({p[i], p[i] + tangent(i) * d / 3, p[i + 1] - tangent(i + 1) * d / 3, p[i + 1]});
  }
  return path;
}

}  // namespace wisp::vector
