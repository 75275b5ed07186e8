// Cubic Bezier evaluation, splitting and flattening (see bezier.hpp).
#include "diffusion/bezier.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::diffusion {

using Eigen::Vector2d;

namespace {

// Largest distance of the two inner control points from the chord p0-p3: the Bezier curve lies
// inside its control polygon's hull, so this bounds the curve's distance from the chord.
double flatness(const Cubic& p) {
  const Vector2d d = p[3] - p[0];
  const double len = d.norm();
  if (len < 1e-12) return std::max((p[1] - p[0]).norm(), (p[2] - p[0]).norm());
  const auto dist = [&](const Vector2d& q) {
    const Vector2d v = q - p[0];
    return std::abs(d.x() * v.y() - d.y() * v.x()) / len;
  };
  return std::max(dist(p[1]), dist(p[2]));
}

// Appends the end points of the pieces of c, whose parameters on the path are [t0, t1].
void flatten_cubic(const Cubic& c, double t0, double t1, double tolerance, int depth,
                   std::vector<PathSample>& out) {
  // Depth 24 splits a cubic into 16 M pieces: far below any tolerance we use, and a guard
  // against non-finite input.
  if (depth >= 24 || flatness(c) <= tolerance) {
    out.push_back({c[3], t1});
    return;
  }
  const auto [left, right] = subdivide(c);
  const double tm = 0.5 * (t0 + t1);
  flatten_cubic(left, t0, tm, tolerance, depth + 1, out);
  flatten_cubic(right, tm, t1, tolerance, depth + 1, out);
}

}  // namespace

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

std::array<Cubic, 2> split(const Cubic& c, double u) {
  const Vector2d p01 = c[0] + u * (c[1] - c[0]), p12 = c[1] + u * (c[2] - c[1]),
                 p23 = c[2] + u * (c[3] - c[2]);
  const Vector2d p012 = p01 + u * (p12 - p01), p123 = p12 + u * (p23 - p12);
  const Vector2d m = p012 + u * (p123 - p012);
  return {Cubic{c[0], p01, p012, m}, Cubic{m, p123, p23, c[3]}};
}

std::array<Cubic, 2> subdivide(const Cubic& c) {
  const Vector2d p01 = 0.5 * (c[0] + c[1]), p12 = 0.5 * (c[1] + c[2]), p23 = 0.5 * (c[2] + c[3]);
  const Vector2d p012 = 0.5 * (p01 + p12), p123 = 0.5 * (p12 + p23);
  const Vector2d m = 0.5 * (p012 + p123);
  return {Cubic{c[0], p01, p012, m}, Cubic{m, p123, p23, c[3]}};
}

Cubic sub_cubic(const Cubic& c, double u0, double u1) {
  if (u0 <= 0 && u1 >= 1) return c;
  const Cubic right = u0 > 0 ? split(c, u0)[1] : c;
  if (u1 >= 1) return right;
  return split(right, (u1 - u0) / (1 - u0))[0];
}

Cubic reversed(const Cubic& c) {
  return {c[3], c[2], c[1], c[0]};
}

Cubic line_cubic(const Vector2d& a, const Vector2d& b) {
  return {a, a + (b - a) / 3.0, a + 2.0 * (b - a) / 3.0, b};
}

Eigen::AlignedBox2d bounds(const Cubic& c) {
  Eigen::AlignedBox2d box;
  for (const Vector2d& p : c) box.extend(p);
  return box;
}

int flatten_pieces(const Cubic& c, double tolerance, int max_pieces) {
  const double m = std::max((c[0] - 2 * c[1] + c[2]).norm(), (c[1] - 2 * c[2] + c[3]).norm());
  const double n = std::ceil(std::sqrt(0.75 * m / tolerance));
  if (!(n >= 1)) return 1;  // also catches NaN
  return int(std::min<double>(n, max_pieces));
}

void BezierPath::append(const Cubic& c) {
  if (points.empty()) points.push_back(c[0]);
  points.insert(points.end(), c.begin() + 1, c.end());
}

Vector2d eval(const BezierPath& path, double s) {
  const int k = path.piece_count();
  if (k == 0) return path.points.empty() ? Vector2d::Zero() : path.points.front();
  const double x = std::clamp(s, 0.0, 1.0) * k;
  const int i = std::min(k - 1, int(std::floor(x)));
  return eval(path.piece(i), x - i);
}

std::vector<PathSample> flatten(const BezierPath& path, double tolerance) {
  std::vector<PathSample> out;
  const int k = path.piece_count();
  if (k == 0) return out;
  out.push_back({path.points.front(), 0.0});
  for (int s = 0; s < k; ++s)
    flatten_cubic(path.piece(s), double(s) / k, double(s + 1) / k, tolerance, 0, out);
  out.back().t = 1.0;
  return out;
}

}  // namespace wisp::diffusion
