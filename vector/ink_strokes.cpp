// Ink strokes from the arrangement's lines (see ink_strokes.hpp).
#include "vector/ink_strokes.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "vector/stroke_fit.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

double ink_scale(const InkStyle& style, int width, int height) {
  return std::min(width, height) / std::max(1e-9, style.reference_size);
}

double root_factor(const InkStyle& style, double v) {
  const auto fade = [](double x, double over, double floor) {
    if (!(over > 0)) return 1.0;
    const double f = std::clamp(x / over, 0.0, 1.0);
    return floor + (1 - floor) * 0.5 * (1 - std::cos(M_PI * f));
  };
  return fade(v, style.root_fade, style.root_width) * fade(1 - v, style.tip_fade, style.tip_width);
}

namespace {

double centre_to_strand(const Wisp& wisp, double t) {
  const auto& su = wisp.centre.strand_u;
  if (su.empty()) return t;
  const double x = std::clamp(t, 0.0, 1.0) * (su.size() - 1);
  const int i = std::min(int(su.size()) - 2, int(x));
  if (i < 0) return su[0];
  return su[i] + (x - i) * (su[i + 1] - su[i]);
}

double nearest_t(const std::vector<OutlineVertex>& poly, const Vector2d& p) {
  double best = 1e300, t = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const OutlineVertex &a = poly[i], &b = poly[(i + 1) % poly.size()];
    const Vector2d d = b.p - a.p;
    const double len2 = d.squaredNorm();
    const double f = len2 > 0 ? std::clamp((p - a.p).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (a.p + f * d - p).squaredNorm();
    if (dist < best) best = dist, t = a.t + f * (b.t - a.t);
  }
  return t;
}

// Keeps the stops that linear interpolation between their neighbours does not reproduce to
// within `tol` px (a greedy pass).
std::vector<std::pair<double, double>> thin(const std::vector<std::pair<double, double>>& in,
                                            double tol) {
  if (in.size() <= 2) return in;
  std::vector<std::pair<double, double>> out = {in.front()};
  size_t anchor = 0;
  for (size_t i = 2; i < in.size(); ++i) {
    // Can the span anchor -> i replace every stop between them?
    bool ok = true;
    const auto &a = in[anchor], &b = in[i];
    for (size_t j = anchor + 1; j < i && ok; ++j) {
      const double f = b.first > a.first ? (in[j].first - a.first) / (b.first - a.first) : 0.0;
      ok = std::abs(a.second + f * (b.second - a.second) - in[j].second) <= tol;
    }
    if (!ok) {
      out.push_back(in[i - 1]);
      anchor = i - 1;
    }
  }
  out.push_back(in.back());
  return out;
}

}  // namespace

double strand_parameter_near(const Wisp& wisp, const Vector2d& p) {
  return centre_to_strand(wisp, nearest_t(outline_polygon(wisp), p));
}

double width_at(const std::vector<std::pair<double, double>>& stops, double s) {
  if (stops.empty()) return 0;
  if (s <= stops.front().first) return stops.front().second;
  if (s >= stops.back().first) return stops.back().second;
  size_t hi = 1;
  while (stops[hi].first < s) ++hi;
  const auto &a = stops[hi - 1], &b = stops[hi];
  const double f = b.first > a.first ? (s - a.first) / (b.first - a.first) : 0.0;
  return a.second + f * (b.second - a.second);
}

std::vector<InkCurve> ink_curves(const std::vector<Wisp>& wisps, const WispArrangement& arrangement,
                                 const InkStyle& style, int width, int height) {
  std::vector<InkCurve> out;
  const double scale = ink_scale(style, width, height);
  std::unordered_map<int, std::vector<OutlineVertex>> polygons;
  FitOptions fit;
  fit.tolerance = std::max(1e-3, style.fit_tolerance);

  const auto add = [&](const InkLine& line, bool silhouette) {
    const double base = (silhouette ? style.silhouette_width : style.occlusion_width) * scale;
    if (!(base > 0) || line.points.size() < 2) return;
    // Points where the taper starts must be knots of the fit, or a long cubic would spread the
    // taper over its whole length: densify so no two consecutive points are farther apart than a
    // few stroke widths. The widths are taken at every point, so that they do not depend on where
    // the arrangement happened to put the line's vertices.
    std::vector<Vector2d> pts;
    const double max_gap = std::max(1.0, 2 * base);
    for (size_t i = 0; i < line.points.size(); ++i) {
      if (i > 0) {
        const Vector2d a = line.points[i - 1], b = line.points[i];
        const int k = int(std::ceil((b - a).norm() / max_gap));
        for (int j = 1; j < k; ++j) pts.push_back(a + (b - a) * (double(j) / k));
      }
      pts.push_back(line.points[i]);
    }
    const int n = int(pts.size());
    std::vector<double> pw(n, base);
    if (line.wisp >= 0 && line.wisp < int(wisps.size()) &&
        (style.root_fade > 0 || style.tip_fade > 0)) {
      auto it = polygons.find(line.wisp);
      if (it == polygons.end())
        it = polygons.emplace(line.wisp, outline_polygon(wisps[line.wisp])).first;
      for (int i = 0; i < n; ++i)
        pw[i] *=
            root_factor(style, centre_to_strand(wisps[line.wisp], nearest_t(it->second, pts[i])));
    }
    if (!silhouette && !line.closed && style.end_taper > 0) {
      // Arc length from each end.
      std::vector<double> from_start(n, 0.0);
      for (int i = 1; i < n; ++i) from_start[i] = from_start[i - 1] + (pts[i] - pts[i - 1]).norm();
      const double total = from_start.back(), taper = style.end_taper * scale;
      for (int i = 0; i < n; ++i) {
        const double d = std::min(from_start[i], total - from_start[i]);
        const double f = std::clamp(d / taper, 0.0, 1.0);
        pw[i] *= f * f * (3 - 2 * f);
      }
    }
    const FittedPath path = fit_cubics(pts, fit, line.closed);
    if (path.piece_count() == 0) return;
    std::vector<std::pair<double, double>> stops;
    for (size_t i = 0; i < pts.size(); ++i) stops.emplace_back(path.param[i], pw[i]);
    if (line.closed) {
      std::stable_sort(stops.begin(), stops.end());
      stops.emplace_back(1.0, stops.front().second);
    }
    InkCurve c;
    c.points = path.points;
    c.width = thin(stops, 0.05);
    c.silhouette = silhouette;
    c.wisp = line.wisp;
    out.push_back(std::move(c));
  };
  for (const InkLine& l : arrangement.silhouette) add(l, true);
  for (const InkLine& l : arrangement.occlusion) add(l, false);
  return out;
}

}  // namespace wisp::vector
