// Visible regions of wisps from the arrangement's faces (see visible_region.hpp).
#include "vector/visible_region.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::vector {

using Eigen::Vector2d;

VisibleRegions::VisibleRegions(const ArrangementView& view, int wisp_count)
    : regions_(std::max(0, wisp_count)) {
  std::vector<std::vector<Edge>> edges(regions_.size());
  const auto add_ring = [&](int w, const std::vector<Vector2d>& ring) {
    for (size_t i = 0; i < ring.size(); ++i) {
      const Vector2d a = ring[i], b = ring[(i + 1) % ring.size()];
      if (a.y() == b.y()) continue;  // never crossed by a horizontal ray's half-open rule
      edges[w].push_back({a, b});
      regions_[w].box.extend(a);
      regions_[w].box.extend(b);
    }
  };
  for (const ViewFace& f : view.faces) {
    if (f.front < 0 || f.front >= wisp_count || !f.in_view || f.outer.empty()) continue;
    add_ring(f.front, f.outer);
    for (const auto& h : f.holes) add_ring(f.front, h);
  }
  for (size_t w = 0; w < regions_.size(); ++w) {
    Region& r = regions_[w];
    if (edges[w].empty()) continue;
    r.y0 = r.box.min().y();
    const int n = std::max(1, int(std::ceil((r.box.max().y() - r.y0) / r.bin)) + 1);
    r.rows.resize(n);
    for (const Edge& e : edges[w]) {
      const int a = int((std::min(e.a.y(), e.b.y()) - r.y0) / r.bin);
      const int b = int((std::max(e.a.y(), e.b.y()) - r.y0) / r.bin);
      for (int k = std::max(0, a); k <= std::min(n - 1, b); ++k) r.rows[k].push_back(e);
    }
  }
}

bool VisibleRegions::contains(int wisp, const Vector2d& p) const {
  if (wisp < 0 || wisp >= int(regions_.size())) return false;
  const Region& r = regions_[wisp];
  if (r.rows.empty() || !r.box.contains(p)) return false;
  const int k = int((p.y() - r.y0) / r.bin);
  if (k < 0 || k >= int(r.rows.size())) return false;
  bool in = false;
  for (const Edge& e : r.rows[k]) {
    if ((e.a.y() > p.y()) != (e.b.y() > p.y()) &&
        p.x() < e.a.x() + (p.y() - e.a.y()) * (e.b.x() - e.a.x()) / (e.b.y() - e.a.y()))
      in = !in;
  }
  return in;
}

bool VisibleRegions::crosses(int wisp, const Vector2d& a, const Vector2d& b) const {
  if (wisp < 0 || wisp >= int(regions_.size())) return false;
  const Region& r = regions_[wisp];
  if (r.rows.empty()) return false;
  const auto cross = [](const Vector2d& u, const Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const int k0 = std::max(0, int(std::floor((std::min(a.y(), b.y()) - r.y0) / r.bin)));
  const int k1 = std::min(int(r.rows.size()) - 1, int((std::max(a.y(), b.y()) - r.y0) / r.bin));
  const Vector2d d = b - a;
  for (int k = k0; k <= k1; ++k)
    for (const Edge& e : r.rows[k]) {
      const Vector2d f = e.b - e.a;
      const double d1 = cross(d, e.a - a), d2 = cross(d, e.b - a);
      const double d3 = cross(f, a - e.a), d4 = cross(f, b - e.a);
      if ((d1 > 0) != (d2 > 0) && (d3 > 0) != (d4 > 0)) return true;
    }
  return false;
}

std::vector<std::pair<double, double>> VisibleRegions::active(int wisp,
                                                              const diffusion::BezierPath& path,
                                                              double step_px) const {
  std::vector<std::pair<double, double>> out;
  const int k = path.piece_count();
  if (k == 0) return out;
  const auto at = [&](double s) { return diffusion::eval(path, s); };
  // Samples: per cubic, enough for `step_px` along its control polygon.
  std::vector<double> s;
  for (int i = 0; i < k; ++i) {
    const diffusion::Cubic c = path.piece(i);
    double len = 0;
    for (int j = 0; j < 3; ++j) len += (c[j + 1] - c[j]).norm();
    const int n = std::max(1, int(std::ceil(len / step_px)));
    for (int j = 0; j < n; ++j) s.push_back((i + double(j) / n) / k);
  }
  s.push_back(1.0);
  double open = -1;
  bool prev = false;
  for (size_t i = 0; i < s.size(); ++i) {
    const bool in = contains(wisp, at(s[i]));
    if (i > 0 && in != prev) {
      double lo = s[i - 1], hi = s[i];
      // Locate the change to ~1e-4 px.
      const double len = (at(hi) - at(lo)).norm();
      const int iters = std::clamp(int(std::ceil(std::log2(std::max(1.0, len / 1e-4)))), 1, 30);
      for (int it = 0; it < iters; ++it) {
        const double m = 0.5 * (lo + hi);
        (contains(wisp, at(m)) == prev ? lo : hi) = m;
      }
      const double x = 0.5 * (lo + hi);
      if (in)
        open = x;
      else
        out.emplace_back(open, x);
    } else if (i == 0 && in) {
      open = 0;
    }
    prev = in;
  }
  if (prev) out.emplace_back(open, 1.0);
  // Drop slivers that cannot touch a pixel link.
  std::vector<std::pair<double, double>> kept;
  for (const auto& iv : out)
    if (iv.second > iv.first) kept.push_back(iv);
  return kept;
}

std::vector<std::pair<double, double>> intersect_intervals(
    const std::vector<std::pair<double, double>>& a,
    const std::vector<std::pair<double, double>>& b) {
  std::vector<std::pair<double, double>> out;
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double lo = std::max(a[i].first, b[j].first), hi = std::min(a[i].second, b[j].second);
    if (hi > lo) out.emplace_back(lo, hi);
    (a[i].second < b[j].second ? i : j)++;
  }
  return out;
}

}  // namespace wisp::vector
