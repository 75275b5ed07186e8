// Band and anime highlight shapes (see highlights.hpp).
#include "vector/highlights.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "vector/chart_contour.hpp"
#include "vector/polygon.hpp"

namespace wisp::vector {

using Eigen::Vector2d;
using Eigen::Vector3d;

std::vector<ChartPolygon> band_highlights(const WispChart& chart, const std::vector<double>& ts,
                                          const HighlightStyle& style, const Vector3d& light) {
  std::vector<ChartPolygon> out;
  if (ts.size() < 3) return out;
  const double umax = std::clamp(style.max_width, 0.05, 1.0);
  const int nu = 17;
  ChartGrid g;
  g.t = ts;
  for (int j = 0; j < nu; ++j) g.u.push_back(-umax + 2 * umax * j / (nu - 1));
  g.value.resize(g.t.size() * nu);
  const auto field = [&](const TubeFrame& f, double u) {
    return blinn(tube_normal(f, u), light, f.V, style.shininess);
  };
  for (size_t i = 0; i < g.t.size(); ++i) {
    const TubeFrame f = chart.frame(g.t[i]);
    for (int j = 0; j < nu; ++j) {
      const bool border = i == 0 || i + 1 == g.t.size() || j == 0 || j + 1 == nu;
      g.value[i * nu + j] = border ? -1.0 : field(f, g.u[j]);
    }
  }
  const double tb = g.t[1], te = g.t[g.t.size() - 2], ub = g.u[1], ue = g.u[nu - 2];
  const auto exact = [&](double t, double u) {
    if (t < tb || t > te || u < ub || u > ue) return -1.0;  // the forced border
    return field(chart.frame(t), u);
  };
  for (ChartContour& c : chart_contours(g, style.threshold, exact)) {
    if (!c.closed || c.tu.size() < 3) continue;
    // Specks below about a pixel are not worth a curve.
    double area_px = 0;
    for (size_t i = 0, j = c.tu.size() - 1; i < c.tu.size(); j = i++) {
      const Vector2d a = chart.point(c.tu[j].x(), c.tu[j].y()),
                     b = chart.point(c.tu[i].x(), c.tu[i].y());
      area_px += a.x() * b.y() - b.x() * a.y();
    }
    if (std::abs(0.5 * area_px) < 1.0) continue;
    if (signed_area(c.tu) < 0) std::reverse(c.tu.begin(), c.tu.end());
    out.push_back(std::move(c.tu));
  }
  return out;
}

std::optional<AnimeCandidate> anime_candidate(const WispChart& chart, const std::vector<double>& ts,
                                              const HighlightStyle& style, const Vector3d& light,
                                              const Vector3d& head_centre) {
  if (ts.size() < 2) return std::nullopt;
  std::vector<double> v(ts.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    const Vector3d T = chart.tangent(ts[i]);
    Vector3d out = chart.world(ts[i]) - head_centre;
    out -= out.dot(T) * T;
    const Vector3d N = out.norm() > 1e-12 ? Vector3d(out.normalized()) : chart.frame(ts[i]).C;
    v[i] = shin_specular(N, -T, light, style.shin_weight, style.shininess);
  }
  const size_t peak = size_t(std::max_element(v.begin(), v.end()) - v.begin());
  if (!(v[peak] > style.threshold)) return std::nullopt;
  size_t a = peak, b = peak;
  while (a > 0 && v[a - 1] > style.threshold) --a;
  while (b + 1 < v.size() && v[b + 1] > style.threshold) ++b;
  // The crossings, interpolated between samples.
  const auto cross = [&](size_t in, size_t out) {
    const double f = (v[in] - style.threshold) / std::max(1e-12, v[in] - v[out]);
    return ts[in] + std::clamp(f, 0.0, 1.0) * (ts[out] - ts[in]);
  };
  AnimeCandidate c;
  c.t0 = a > 0 ? cross(a, a - 1) : ts[a];
  c.t1 = b + 1 < v.size() ? cross(b, b + 1) : ts[b];
  c.t_peak = ts[peak];
  // A stretch that runs over most of the wisp is a sheen, not a highlight: keep its middle part.
  const double span = chart.t_end() - chart.t_begin(), longest = 0.3 * span;
  if (c.t1 - c.t0 > longest) {
    c.t0 = std::max(c.t0, c.t_peak - 0.5 * longest);
    c.t1 = std::min(c.t1, c.t0 + longest);
    c.t0 = c.t1 - longest;
  }
  const double shortest = 0.06 * span;
  if (c.t1 - c.t0 < shortest) {
    const double m = 0.5 * (c.t0 + c.t1);
    c.t0 = std::max(chart.t_begin(), m - 0.5 * shortest);
    c.t1 = std::min(chart.t_end(), c.t0 + shortest);
  }
  c.peak_px = chart.point(c.t_peak, 0);
  return c;
}

std::vector<int> cluster_candidates(const std::vector<AnimeCandidate>& cands, double link_px,
                                    int min_cluster) {
  const int n = int(cands.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<int(int)> root = [&](int i) {
    return parent[i] == i ? i : parent[i] = root(parent[i]);
  };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if ((cands[i].peak_px - cands[j].peak_px).norm() <= link_px) {
        const int a = root(i), b = root(j);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
  std::vector<int> size(n, 0), out(n, -1);
  for (int i = 0; i < n; ++i) ++size[root(i)];
  for (int i = 0; i < n; ++i)
    if (size[root(i)] >= std::max(1, min_cluster)) out[i] = root(i);
  return out;
}

ChartPolygon anime_zigzag(const AnimeCandidate& c, const HighlightStyle& style) {
  const double umax = std::clamp(style.max_width, 0.05, 1.0);
  const int n = std::max(1, style.teeth);
  const double len = c.t1 - c.t0;
  ChartPolygon p;
  // Lower (tip-side) edge, u ascending: teeth reach t1, valleys at 45% of the length.
  for (int j = 0; j <= 2 * n; ++j) {
    const double u = -umax + umax * j / n;
    p.emplace_back(j % 2 ? c.t1 : c.t0 + 0.55 * len, u);
  }
  // Upper (root-side) edge, u descending: shallow notches.
  for (int j = 2 * n; j >= 0; --j) {
    const double u = -umax + umax * j / n;
    p.emplace_back(j % 2 ? c.t0 + 0.2 * len : c.t0, u);
  }
  if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

}  // namespace wisp::vector
