// Brute-force raster reference: scanline coverage per wisp, per-pixel depth from the band cells,
// a z-buffer for the front-most wisp.
#include "tests/vector/raster_reference.hpp"

#include <limits>

namespace wisp::test {

using Eigen::Vector2d;

namespace {

double line_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d d = b - a;
  const double n = d.norm();
  if (n == 0) return (p - a).norm();
  return std::abs(d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x())) / n;
}

template <class Ring>
int winding(const Ring& q, int n, const Vector2d& p) {
  int wind = 0;
  for (int i = 0; i < n; ++i) {
    const Vector2d &a = q[i], &b = q[(i + 1) % n];
    const double c = (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && c > 0) ++wind;
    } else if (b.y() <= p.y() && c < 0) {
      --wind;
    }
  }
  return wind;
}

double segment_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d d = b - a;
  const double l =
      d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + l * d - p).norm();
}

}  // namespace

int winding_number(const std::vector<Vector2d>& ring, const Vector2d& p) {
  return winding(ring, int(ring.size()), p);
}

double reference_depth(const vector::Wisp& w, const Vector2d& p, double margin) {
  double best = std::numeric_limits<double>::infinity();
  const auto& s = w.sections;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const Vector2d q[4] = {s[i].left, s[i + 1].left, s[i + 1].right, s[i].right};
    if (winding(q, 4, p) == 0) continue;
    if (margin > 0) {
      double d = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 4; ++k) d = std::min(d, segment_distance(p, q[k], q[(k + 1) % 4]));
      if (d < margin) continue;
    }
    const double d0 = line_distance(p, s[i].left, s[i].right);
    const double d1 = line_distance(p, s[i + 1].left, s[i + 1].right);
    const double z = d0 + d1 > 0 ? (d1 * s[i].depth + d0 * s[i + 1].depth) / (d0 + d1) : s[i].depth;
    best = std::min(best, z);
  }
  if (best < std::numeric_limits<double>::infinity() || margin > 0) return best;
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& sec : s) {
    const double d = (sec.centre - p).norm();
    if (d < nearest) nearest = d, best = sec.depth;
  }
  return best;
}

Raster reference_front(const std::vector<vector::Wisp>& wisps, int width, int height) {
  Raster r{width, height, std::vector<int>(size_t(width) * height, -1)};
  std::vector<double> zbuf(size_t(width) * height, std::numeric_limits<double>::infinity());
  for (int w = 0; w < int(wisps.size()); ++w) {
    std::vector<Vector2d> ring;
    for (const auto& v : vector::outline_polygon(wisps[w])) ring.push_back(v.p);
    scan_polygons({ring}, width, height, true, [&](int x, int y) {
      const double z = reference_depth(wisps[w], Vector2d(x + 0.5, y + 0.5));
      double& zb = zbuf[size_t(y) * width + x];
      if (z < zb) zb = z, r.at(x, y) = w;
    });
  }
  return r;
}

Raster arrangement_front(const vector::ArrangementView& view, int width, int height) {
  Raster r{width, height, std::vector<int>(size_t(width) * height, -1)};
  for (const auto& f : view.faces) {
    if (f.front < 0 || f.unbounded) continue;
    std::vector<std::vector<Vector2d>> rings = {f.outer};
    rings.insert(rings.end(), f.holes.begin(), f.holes.end());
    scan_polygons(rings, width, height, false, [&](int x, int y) { r.at(x, y) = f.front; });
  }
  return r;
}

Raster mask_raster(const vector::HairMask& mask, int width, int height) {
  Raster r{width, height, std::vector<int>(size_t(width) * height, 0)};
  for (const auto& poly : mask.polygons) {
    std::vector<std::vector<Vector2d>> rings = {poly.outer};
    rings.insert(rings.end(), poly.holes.begin(), poly.holes.end());
    scan_polygons(rings, width, height, false, [&](int x, int y) { r.at(x, y) = 1; });
  }
  return r;
}

}  // namespace wisp::test
