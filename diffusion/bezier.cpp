// Cubic Bezier evaluation and adaptive flattening (see bezier.hpp).
#include "diffusion/bezier.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::diffusion {
namespace {

// Largest distance of the two inner control points from the chord p0-p3: the Bezier curve lies
// inside its control polygon's hull, so this bounds the curve's distance from the chord.
double flatness(const Eigen::Vector2d* p) {
  const Eigen::Vector2d d = p[3] - p[0];
  const double len = d.norm();
  if (len < 1e-12) return std::max((p[1] - p[0]).norm(), (p[2] - p[0]).norm());
  const auto dist = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector2d v = q - p[0];
    return std::abs(d.x() * v.y() - d.y() * v.x()) / len;
  };
  return std::max(dist(p[1]), dist(p[2]));
}

void subdivide(const Eigen::Vector2d* p, double t0, double t1, double tolerance, int depth,
               std::vector<PathSample>& out) {
  // Depth 24 splits a cubic into 16 M pieces: far below any tolerance we use, and a guard
  // against non-finite input.
  if (depth >= 24 || flatness(p) <= tolerance) {
    out.push_back({p[3], t1});
    return;
  }
  const Eigen::Vector2d p01 = 0.5 * (p[0] + p[1]), p12 = 0.5 * (p[1] + p[2]),
                        p23 = 0.5 * (p[2] + p[3]);
  const Eigen::Vector2d p012 = 0.5 * (p01 + p12), p123 = 0.5 * (p12 + p23);
  const Eigen::Vector2d mid = 0.5 * (p012 + p123);
  const Eigen::Vector2d left[4] = {p[0], p01, p012, mid};
  const Eigen::Vector2d right[4] = {mid, p123, p23, p[3]};
  const double tm = 0.5 * (t0 + t1);
  subdivide(left, t0, tm, tolerance, depth + 1, out);
  subdivide(right, tm, t1, tolerance, depth + 1, out);
}

}  // namespace

Eigen::Vector2d eval_cubic(const Eigen::Vector2d* p, double s) {
  const double u = 1 - s;
  return u * u * u * p[0] + 3 * u * u * s * p[1] + 3 * u * s * s * p[2] + s * s * s * p[3];
}

std::vector<PathSample> flatten_path(const std::vector<Eigen::Vector2d>& points, double tolerance) {
  std::vector<PathSample> out;
  if (points.size() < 4) return out;
  const int k = int(points.size() - 1) / 3;
  out.push_back({points[0], 0.0});
  for (int s = 0; s < k; ++s)
    subdivide(&points[3 * s], double(s) / k, double(s + 1) / k, tolerance, 0, out);
  out.back().t = 1.0;
  return out;
}

}  // namespace wisp::diffusion
