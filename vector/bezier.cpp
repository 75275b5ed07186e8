// Cubic Bezier evaluation and the centripetal Catmull-Rom to Bezier conversion.
#include "vector/bezier.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::vector {

using Eigen::Vector2d;

Vector2d eval(const Cubic& c, double u) {
  const double v = 1 - u;
  return v * v * v * c[0] + 3 * v * v * u * c[1] + 3 * v * u * u * c[2] + u * u * u * c[3];
}

Vector2d derivative(const Cubic& c, double u) {
  const double v = 1 - u;
  return 3 * (v * v * (c[1] - c[0]) + 2 * v * u * (c[2] - c[1]) + u * u * (c[3] - c[2]));
}

Vector2d second_derivative(const Cubic& c, double u) {
  return 6 * ((1 - u) * (c[2] - 2 * c[1] + c[0]) + u * (c[3] - 2 * c[2] + c[1]));
}

Cubic line_cubic(const Vector2d& a, const Vector2d& b) {
  return {a, a + (b - a) / 3.0, a + 2.0 * (b - a) / 3.0, b};
}

int flatten_pieces(const Cubic& c, double tolerance, int max_pieces) {
  const double m = std::max((c[0] - 2 * c[1] + c[2]).norm(), (c[1] - 2 * c[2] + c[3]).norm());
  const double n = std::ceil(std::sqrt(0.75 * m / tolerance));
  if (!(n >= 1)) return 1;  // also catches NaN
  return int(std::min<double>(n, max_pieces));
}

std::vector<Cubic> catmull_rom_spans(const std::vector<Vector2d>& p) {
  const int n = int(p.size());
  std::vector<Cubic> spans;
  if (n < 2) return spans;
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
  spans.reserve(n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    const double d = knot(i);
    spans.push_back({p[i], p[i] + tangent(i) * d / 3, p[i + 1] - tangent(i + 1) * d / 3, p[i + 1]});
  }
  return spans;
}

}  // namespace wisp::vector
