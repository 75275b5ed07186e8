// Band and anime highlight shapes (see highlights.hpp).
#include "vector/highlights.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "diffusion/bezier.hpp"
#include "vector/chart_contour.hpp"
#include "vector/polygon.hpp"
#include "vector/stroke_fit.hpp"

namespace wisp::vector {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// The closed regions where field(t, u) > level over the wisp, sampled at `ts` and 17 lateral
// positions spanning |u| <= umax, plus a forced border (one row and column outside) so every
// region closes, at the border at most. Regions below about a pixel are dropped.
std::vector<ChartPolygon> closed_regions(const WispChart& chart, const std::vector<double>& ts,
                                         double umax, double level,
                                         const std::function<double(double, double)>& field) {
  std::vector<ChartPolygon> out;
  if (ts.size() < 3) return out;
  const int nu = 17;
  ChartGrid g;
  g.t = ts;
  const double du = 2 * umax / (nu - 1);
  g.u.push_back(-umax - du);
  for (int j = 0; j < nu; ++j) g.u.push_back(-umax + j * du);
  g.u.push_back(umax + du);
  const size_t n = g.u.size();
  g.value.resize(g.t.size() * n);
  const double outside = level - 1;
  for (size_t i = 0; i < g.t.size(); ++i)
    for (size_t j = 0; j < n; ++j) {
      const bool border = i == 0 || i + 1 == g.t.size() || j == 0 || j + 1 == n;
      g.value[i * n + j] = border ? outside : field(g.t[i], g.u[j]);
    }
  const double tb = g.t[1], te = g.t[g.t.size() - 2];
  const auto exact = [&](double t, double u) {
    if (t < tb || t > te || u < -umax || u > umax) return outside;  // the forced border
    return field(t, u);
  };
  for (ChartContour& c : chart_contours(g, level, exact)) {
    if (!c.closed || c.tu.size() < 3) continue;
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

double umax_of(const HighlightStyle& style) {
  return std::clamp(style.max_width, 0.05, 1.0);
}

}  // namespace

std::vector<ChartPolygon> band_highlights(const WispChart& chart, const std::vector<double>& ts,
                                          const HighlightStyle& style, const Vector3d& light) {
  return closed_regions(chart, ts, umax_of(style), style.threshold, [&](double t, double u) {
    const TubeFrame f = chart.frame(t);
    return blinn(tube_normal(f, u), light, f.V, style.shininess);
  });
}

double AnimeBand::field(const Vector3d& p) const {
  const Vector3d d = p - centre;
  const double r = d.norm();
  if (!(r > 0)) return -1;
  const Vector3d n = d / r;
  const double lat = std::asin(std::clamp(n.dot(up), -1.0, 1.0));
  const double lon = std::atan2(n.dot(side), n.dot(front));
  // Widest at H's longitude, closing to a point at +-extent.
  const double x = lon / extent;
  const double half = half_width * std::sqrt(std::max(0.0, 1 - x * x));
  // Teeth below the lower edge: a triangle wave in longitude, its tips between valleys at
  // multiples of the period from H's longitude.
  const double phase = lon / period - std::floor(lon / period);
  const double tip = 1 - std::abs(2 * phase - 1);
  const double low = latitude - half - tooth * 2 * half * tip, high = latitude + half;
  return std::min({lat - low, high - lat, extent - std::abs(lon)});
}

AnimeBand anime_band(const HighlightStyle& style, const sim::ProjectedFrame& frame,
                     const Vector3d& head_centre, double head_radius, double wisp_width) {
  AnimeBand b;
  b.centre = head_centre;
  b.up = frame.head_up.norm() > 0 ? Vector3d(frame.head_up.normalized()) : Vector3d::UnitY();
  const Vector3d L =
      frame.light_dir.norm() > 0 ? Vector3d(frame.light_dir.normalized()) : Vector3d::UnitZ();
  const Vector3d V = (frame.eye - head_centre).norm() > 0
                         ? Vector3d((frame.eye - head_centre).normalized())
                         : Vector3d::UnitZ();
  Vector3d H = L + V;
  H = H.norm() > 1e-9 ? Vector3d(H.normalized()) : V;
  // H's horizontal direction; with H along the crown axis, the eye's.
  Vector3d front = H - H.dot(b.up) * b.up;
  if (front.norm() < 1e-6) front = V - V.dot(b.up) * b.up;
  if (front.norm() < 1e-6) front = b.up.unitOrthogonal();
  b.front = front.normalized();
  b.side = b.up.cross(b.front);
  const double deg = M_PI / 180;
  b.latitude = std::asin(std::clamp(H.dot(b.up), -1.0, 1.0)) + style.band_shift_deg * deg;
  b.half_width = 0.5 * style.band_width_deg * deg;
  b.extent = std::max(1.0, style.band_extent_deg) * deg;
  b.period = std::max(1e-3, wisp_width / std::max(1e-6, head_radius)) / std::max(1, style.teeth);
  b.tooth = style.tooth_depth;
  b.focal_px = frame.focal_px > 0 ? frame.focal_px : 1;
  return b;
}

std::vector<ChartPolygon> anime_highlights(const WispChart& chart, const std::vector<double>& ts,
                                           const HighlightStyle& style, const AnimeBand& band) {
  // A point of the wisp's surface: the centre line offset across by the wisp's half-width in
  // scene units along the tube's lateral axis, which projects onto the on-screen u direction.
  return closed_regions(chart, ts, umax_of(style), 0.0, [&](double t, double u) {
    const double half_px = 0.5 * (chart.point(t, 1) - chart.point(t, -1)).norm();
    const double half = half_px * chart.depth(t) / band.focal_px;
    return band.field(chart.world(t) + u * half * chart.frame(t).B);
  });
}

std::vector<Vector2d> densify(const ChartPolygon& poly, double step_t, double step_u) {
  std::vector<Vector2d> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    const int n = std::max({1, int(std::ceil(std::abs(b.x() - a.x()) / step_t)),
                            int(std::ceil(std::abs(b.y() - a.y()) / step_u))});
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (double(k) / n));
  }
  return out;
}

std::vector<Vector2d> highlight_outline(const WispChart& chart, size_t sample_count,
                                        const ChartPolygon& poly) {
  const double step_t = (chart.t_end() - chart.t_begin()) / std::max<size_t>(8, sample_count);
  return densify(poly, step_t, 0.1);
}

void HighlightCover::add(int wisp, std::vector<Vector2d> ring) {
  if (ring.size() < 3) return;
  Ring r{wisp, std::move(ring), {}};
  for (const Vector2d& p : r.points) r.box.extend(p);
  rings_.push_back(std::move(r));
}

bool HighlightCover::contains(const Vector2d& p, int except) const {
  for (const Ring& r : rings_)
    if (r.wisp != except && r.box.contains(p) && inside_polygon(r.points, p) &&
        regions_.contains(r.wisp, p))
      return true;
  return false;
}

std::vector<diffusion::ColorStop> HighlightCover::outside_stops(
    const Wisp& wisp, int w, const Eigen::Vector3f& shadow,
    const Eigen::Vector3f& highlight) const {
  const diffusion::BezierPath& path = wisp.outline;
  std::vector<diffusion::ColorStop> plain = {{0.0, shadow}, {1.0, shadow}};
  Eigen::AlignedBox2d near;
  for (const Ring& r : rings_)
    if (r.wisp != w) near.extend(r.box);
  if (rings_.empty() || path.piece_count() == 0 || !near.intersects(wisp.bounds)) return plain;
  // The point 0.75 px outside the outline at s: the interior lies on diffusion's left of the
  // path, so outside is its right, (d.y, -d.x).
  const auto beyond = [&](double s) -> Vector2d {
    const double e = 1e-5;
    const Vector2d d =
        diffusion::eval(path, std::min(1.0, s + e)) - diffusion::eval(path, std::max(0.0, s - e));
    if (!(d.norm() > 0)) return diffusion::eval(path, s);
    return diffusion::eval(path, s) + 0.75 * Vector2d(d.y(), -d.x()).normalized();
  };
  const auto lit = [&](double s) { return contains(beyond(s), w); };
  double length = 0;
  for (size_t i = 1; i < path.points.size(); ++i)
    length += (path.points[i] - path.points[i - 1]).norm();
  const int m = std::max(16, int(std::ceil(length)));
  std::vector<diffusion::ColorStop> out;
  bool prev = lit(0);
  bool any = prev;
  out.push_back({0.0, prev ? highlight : shadow});
  for (int j = 1; j <= m; ++j) {
    const double s1 = double(j) / m;
    const bool now = lit(s1);
    if (now != prev) {
      double lo = double(j - 1) / m, hi = s1;
      for (int k = 0; k < 14; ++k) {
        const double mid = 0.5 * (lo + hi);
        (lit(mid) == prev ? lo : hi) = mid;
      }
      const double s = 0.5 * (lo + hi);
      out.push_back({s, prev ? highlight : shadow});
      out.push_back({s, now ? highlight : shadow});
      prev = now;
      any = true;
    }
  }
  out.push_back({1.0, prev ? highlight : shadow});
  return any ? out : plain;
}

}  // namespace wisp::vector
