// Tracing the hair base from its field (see hair_base.hpp).
#include "vector/hair_base.hpp"

#include <algorithm>
#include <cmath>

#include "diffusion/bezier.hpp"
#include "vector/chart_contour.hpp"
#include "vector/polygon.hpp"
#include "vector/stroke_fit.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

HairBase trace_hair_base(const std::function<double(const Vector2d&)>& field,
                         std::function<double(const Vector2d&)> depth,
                         const Eigen::AlignedBox2d& box, const HairBaseOptions& options) {
  HairBase base;
  base.depth = std::move(depth);
  if (box.isEmpty() || !box.min().allFinite() || !box.max().allFinite()) return base;
  const double cell = std::max(0.25, options.cell_px);
  // Grid over the box plus two cells; the outermost nodes are forced outside, so every contour
  // closes.
  ChartGrid g;
  const Vector2d lo = box.min() - Vector2d::Constant(2 * cell);
  const int nx = int(std::ceil(box.sizes().x() / cell)) + 5;
  const int ny = int(std::ceil(box.sizes().y() / cell)) + 5;
  for (int i = 0; i < nx; ++i) g.t.push_back(lo.x() + i * cell);
  for (int j = 0; j < ny; ++j) g.u.push_back(lo.y() + j * cell);
  g.value.resize(size_t(nx) * ny);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const bool border = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
      g.value[size_t(i) * ny + j] = border ? -1.0 : field(Vector2d(g.t[i], g.u[j]));
    }
  const double tb = g.t[1], te = g.t[nx - 2], ub = g.u[1], ue = g.u[ny - 2];
  const auto exact = [&](double x, double y) {
    if (x < tb || x > te || y < ub || y > ue) return -1.0;
    return field(Vector2d(x, y));
  };
  FitOptions fit;
  fit.tolerance = options.fit_tolerance;
  // With t = x and u = y, chart_contours' "higher values on the left in (t, u)" is the base on
  // the left in (x, y).
  for (ChartContour& c : chart_contours(g, 0.0, exact)) {
    if (!c.closed || c.tu.size() < 3 || std::abs(signed_area(c.tu)) < options.min_area) continue;
    FittedPath path = fit_cubics(c.tu, fit, true);
    if (path.piece_count() == 0) continue;
    std::vector<Vector2d> ring;
    std::vector<double> s;
    for (const diffusion::PathSample& q : diffusion::flatten(path, options.flatten_tolerance)) {
      if (!ring.empty() && (q.p - ring.back()).norm() < 1e-9) continue;
      ring.push_back(q.p);
      s.push_back(q.t);
    }
    if (ring.size() > 1 && (ring.back() - ring.front()).norm() < 1e-9)
      ring.pop_back(), s.pop_back();
    if (ring.size() < 3) continue;
    base.paths.push_back(std::move(path));
    base.rings.push_back(std::move(ring));
    base.ring_s.push_back(std::move(s));
  }
  return base;
}

Eigen::Vector3f base_color(const HairStyle& style) {
  const double tone = std::clamp(style.base.tone, 0.0, 1.0);
  const ShadingStyle& sh = style.shading;
  if (sh.model == ShadingModel::Lit && sh.ramp && sh.ramp->width > 0) {
    const RampBands bands(*sh.ramp, sh.band_threshold);
    return bands.lookup(tone, 0.5).cwiseProduct(sh.ramp_tint);
  }
  return style.shadow + float(tone) * (style.hair - style.shadow);
}

std::vector<diffusion::DiffusionCurve> base_curves(
    const HairBase& base, const std::vector<std::vector<std::pair<double, double>>>& visible,
    const Eigen::Vector3f& color) {
  std::vector<diffusion::DiffusionCurve> out;
  for (size_t i = 0; i < base.paths.size() && i < visible.size(); ++i) {
    if (visible[i].empty()) continue;  // an empty active set would mean everywhere
    diffusion::DiffusionCurve c;
    c.points = base.paths[i].points;
    c.left = {{0.0, color}, {1.0, color}};
    if (base.shade && i < base.rings.size() && i < base.ring_s.size()) {
      const std::vector<Eigen::Vector2d>& ring = base.rings[i];
      c.left.clear();
      Eigen::Vector2d last(INFINITY, INFINITY);
      for (size_t k = 0; k < ring.size(); ++k)
        if ((ring[k] - last).norm() >= 3 || k == 0) {
          c.left.push_back({base.ring_s[i][k], base.shade(ring[k])});
          last = ring[k];
        }
      c.left.push_back({1.0, c.left.front().color});  // closed: back to the start's colour
    }
    c.right = c.left;
    c.right_boundary = diffusion::Boundary::Neumann;
    c.active = visible[i];
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace wisp::vector
