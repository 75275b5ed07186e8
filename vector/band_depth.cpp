// Point location in the band cells of a wisp, and the interpolated depth there.
#include "vector/band_depth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

double distance_to_segment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double l = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + l * ab - p).norm();
}

// Cell i: left_i, left_{i+1}, right_{i+1}, right_i.
std::array<Vector2d, 4> cell(const Wisp& w, int i) {
  const Section &a = w.sections[i], &b = w.sections[i + 1];
  return {a.left, b.left, b.right, a.right};
}

// Crossing-number test (boundary points may go either way; callers tolerate that).
bool inside(const std::array<Vector2d, 4>& q, const Vector2d& p) {
  bool in = false;
  for (int i = 0, j = 3; i < 4; j = i++) {
    if ((q[i].y() > p.y()) != (q[j].y() > p.y())) {
      const double x =
          q[j].x() + (p.y() - q[j].y()) * (q[i].x() - q[j].x()) / (q[i].y() - q[j].y());
      if (p.x() < x) in = !in;
    }
  }
  return in;
}

double distance_to_cell(const std::array<Vector2d, 4>& q, const Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0, j = 3; i < 4; j = i++) d = std::min(d, distance_to_segment(p, q[j], q[i]));
  return d;
}

bool outside_bounds(const std::array<Vector2d, 4>& q, const Vector2d& p, double margin) {
  const double x0 = std::min({q[0].x(), q[1].x(), q[2].x(), q[3].x()});
  const double x1 = std::max({q[0].x(), q[1].x(), q[2].x(), q[3].x()});
  const double y0 = std::min({q[0].y(), q[1].y(), q[2].y(), q[3].y()});
  const double y1 = std::max({q[0].y(), q[1].y(), q[2].y(), q[3].y()});
  return p.x() < x0 - margin || p.x() > x1 + margin || p.y() < y0 - margin || p.y() > y1 + margin;
}

BandHit hit(const Wisp& w, int i, const Vector2d& p) {
  const Section &a = w.sections[i], &b = w.sections[i + 1];
  const Vector2d ab = b.centre - a.centre;
  const double len2 = ab.squaredNorm();
  const double l = len2 > 0 ? std::clamp((p - a.centre).dot(ab) / len2, 0.0, 1.0) : 0.5;
  return {a.depth + l * (b.depth - a.depth), a.t + l * (b.t - a.t)};
}

}  // namespace

BandHit band_depth(const Wisp& w, const Vector2d& p) {
  std::optional<BandHit> best;
  const int cells = int(w.sections.size()) - 1;
  for (int i = 0; i < cells; ++i) {
    const auto q = cell(w, i);
    if (outside_bounds(q, p, 0) || !inside(q, p)) continue;
    const BandHit h = hit(w, i, p);
    if (!best || h.depth < best->depth) best = h;
  }
  if (best) return *best;
  // Rare: p is a rounding error outside every cell. The nearest cell decides.
  int nearest = 0;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < cells; ++i) {
    const double d = distance_to_cell(cell(w, i), p);
    if (d < nearest_distance) nearest_distance = d, nearest = i;
  }
  return hit(w, nearest, p);
}

std::optional<BandHit> band_depth_inside(const Wisp& w, const Vector2d& p, double margin) {
  std::optional<BandHit> best;
  for (int i = 0; i + 1 < int(w.sections.size()); ++i) {
    const auto q = cell(w, i);
    if (outside_bounds(q, p, -margin) || !inside(q, p) || distance_to_cell(q, p) < margin) continue;
    const BandHit h = hit(w, i, p);
    if (!best || h.depth < best->depth) best = h;
  }
  return best;
}

}  // namespace wisp::vector
