// Curves inside a wisp: centre line, band edges, highlights (see inner_curves.hpp).
#include "vector/inner_curves.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "vector/chart_contour.hpp"
#include "vector/polygon.hpp"
#include "vector/stroke_fit.hpp"

namespace wisp::vector {
namespace {

using Eigen::Vector2d;
using Intervals = std::vector<std::pair<double, double>>;
using diffusion::ColorStop;

constexpr double kInnerFitTolerance = 0.1;  // px: interior curves against their exact samples

// Parameter intervals of an open curve (points `tu` at parameters `s`, 0 to 1) where `inside`
// is false; each change is located by bisection on the segment between two points.
Intervals outside_of(const std::vector<Vector2d>& tu, const std::vector<double>& s,
                     const std::function<bool(const Vector2d&)>& inside) {
  Intervals out;
  double open = 0;
  bool prev = true;
  for (size_t i = 0; i < tu.size(); ++i) {
    const bool in = inside(tu[i]);
    if (i == 0) {
      open = 0;
    } else if (in != prev) {
      double lo = 0, hi = 1;
      for (int k = 0; k < 16; ++k) {
        const double m = 0.5 * (lo + hi);
        (inside(tu[i - 1] + m * (tu[i] - tu[i - 1])) == prev ? lo : hi) = m;
      }
      const double x = s[i - 1] + 0.5 * (lo + hi) * (s[i] - s[i - 1]);
      if (!in)
        open = x;
      else if (x > open)
        out.emplace_back(open, x);
    }
    prev = in;
  }
  if (!prev && 1.0 > open) out.emplace_back(open, 1.0);
  return out;
}

// A chart curve mapped to pixels and fitted; `closed` for loops.
struct ChartCurve {
  std::vector<Vector2d> tu;
  FittedPath path;
};

ChartCurve fit_chart_curve(const WispChart& chart, std::vector<Vector2d> tu, bool closed) {
  ChartCurve c;
  std::vector<Vector2d> px;
  px.reserve(tu.size());
  for (const Vector2d& p : tu) px.push_back(chart.point(p.x(), p.y()));
  FitOptions fo;
  fo.tolerance = kInnerFitTolerance;
  c.path = fit_cubics(px, fo, closed);
  c.tu = std::move(tu);
  return c;
}

// Where a curve inside one wisp constrains the solve: where the wisp shows and, for the curves
// that must not paint over its highlights, outside them.
struct Clip {
  const VisibleRegions& regions;
  int wisp;
  const std::vector<ChartPolygon>& highlights;

  Intervals shown(const diffusion::BezierPath& path) const { return regions.active(wisp, path); }

  Intervals shown_outside_highlights(const ChartCurve& c) const {
    Intervals a = shown(c.path);
    if (highlights.empty()) return a;
    const auto in_highlight = [&](const Vector2d& tu) {
      for (const ChartPolygon& p : highlights)
        if (inside_polygon(p, tu)) return true;
      return false;
    };
    return intersect_intervals(a, outside_of(c.tu, c.path.param, in_highlight));
  }
};

void add_centre_line(const WispInterior& wisp, const Clip& clip, InnerCurves& out) {
  std::vector<Vector2d> tu;
  for (double t : *wisp.samples) tu.emplace_back(t, 0.0);
  ChartCurve c = fit_chart_curve(*wisp.chart, std::move(tu), false);
  if (c.path.piece_count() == 0) return;
  diffusion::DiffusionCurve d;
  d.points = c.path.points;
  d.left = stops_along(*wisp.shader, c.tu, c.path.param);
  d.right = d.left;
  d.active = clip.shown_outside_highlights(c);
  if (!d.active.empty()) out.curves.push_back(std::move(d)), ++out.centre_lines;
}

// The ramp's x over the wisp's chart: at the shading samples along it, 17 places across.
ChartGrid ramp_grid(const WispShader& shader, const std::vector<double>& ts) {
  ChartGrid g;
  g.t = ts;
  const int nu = 17;
  for (int j = 0; j < nu; ++j) g.u.push_back(-1.0 + 2.0 * j / (nu - 1));
  g.value.resize(g.t.size() * nu);
  for (size_t i = 0; i < g.t.size(); ++i)
    for (int j = 0; j < nu; ++j) g.value[i * nu + j] = shader.x(g.t[i], g.u[j]);
  return g;
}

// The fitted level set of the ramp's edge between bands `band` and `band + 1`, with each band's
// colours on its side.
diffusion::DiffusionCurve band_edge_curve(const WispShader& shader, const ChartCurve& c, int band,
                                          bool closed) {
  diffusion::DiffusionCurve d;
  d.points = c.path.points;
  // Higher x lies on the chart's left, which is diffusion's right.
  for (size_t i = 0; i < c.tu.size(); ++i) {
    const double t = c.tu[i].x(), u = c.tu[i].y(), s = c.path.param[i];
    d.left.push_back({s, shader.color_in_band(t, u, band)});
    d.right.push_back({s, shader.color_in_band(t, u, band + 1)});
  }
  if (closed) {
    // A loop starts at its sharpest corner: order the stops along the path and close.
    for (auto* side : {&d.left, &d.right}) {
      std::stable_sort(side->begin(), side->end(),
                       [](const ColorStop& a, const ColorStop& b) { return a.t < b.t; });
      side->push_back({1.0, side->front().color});
    }
  }
  return d;
}

void add_band_edges(const WispInterior& wisp, const Clip& clip, InnerCurves& out) {
  const WispShader& shader = *wisp.shader;
  const std::vector<double>& edges = shader.bands()->edges();
  const ChartGrid g = ramp_grid(shader, *wisp.samples);
  const auto exact = [&](double t, double u) { return shader.x(t, u); };
  for (size_t e = 0; e < edges.size(); ++e) {
    for (ChartContour& k : chart_contours(g, edges[e], exact)) {
      ChartCurve c = fit_chart_curve(*wisp.chart, std::move(k.tu), k.closed);
      if (c.path.piece_count() == 0) continue;
      diffusion::DiffusionCurve d = band_edge_curve(shader, c, int(e), k.closed);
      d.active = k.closed ? clip.shown(d) : clip.shown_outside_highlights(c);
      if (!d.active.empty()) out.curves.push_back(std::move(d)), ++out.band_edges;
    }
  }
}

void add_highlights(const WispInterior& wisp, const Clip& clip, const HairStyle& style,
                    InnerCurves& out) {
  const WispChart& chart = *wisp.chart;
  for (const ChartPolygon& p : *wisp.highlights) {
    ChartCurve c = fit_chart_curve(chart, highlight_outline(chart, wisp.samples->size(), p), true);
    if (c.path.piece_count() == 0) continue;
    diffusion::DiffusionCurve d;
    d.points = c.path.points;
    // Counter-clockwise in the chart: the inside is on diffusion's right.
    d.right = {{0.0, style.specular.color}, {1.0, style.specular.color}};
    d.left_boundary = diffusion::Boundary::Neumann;
    d.active = clip.shown(d);
    if (!d.active.empty()) out.curves.push_back(std::move(d)), ++out.highlights;
  }
}

}  // namespace

std::vector<std::vector<ChartPolygon>> highlight_shapes(
    const std::vector<std::unique_ptr<WispChart>>& charts,
    const std::vector<std::vector<double>>& samples, const HairStyle& style,
    const FrameLight& light, const sim::ProjectedFrame& frame) {
  const int n = int(charts.size());
  std::vector<std::vector<ChartPolygon>> highlights(n);
  if (style.specular.shape == HighlightShape::Band) {
    for (int w = 0; w < n; ++w)
      if (charts[w])
        highlights[w] = band_highlights(*charts[w], samples[w], style.specular, light.light);
  } else if (style.specular.shape == HighlightShape::Anime) {
    const AnimeBand band = anime_band(style.specular, frame, light.head_centre, light.head_radius,
                                      style.geometry.width);
    for (int w = 0; w < n; ++w)
      if (charts[w]) highlights[w] = anime_highlights(*charts[w], samples[w], style.specular, band);
  }
  return highlights;
}

void add_inner_curves(const WispInterior& wisp, const VisibleRegions& regions,
                      const HairStyle& style, InnerCurves& out) {
  const Clip clip{regions, wisp.index, *wisp.highlights};
  const bool lit = style.shading.model == ShadingModel::Lit;
  const RampBands* bands = wisp.shader->bands();
  if (lit && style.shading.centre_line) add_centre_line(wisp, clip, out);
  if (lit && bands && style.shading.hard_bands && !bands->edges().empty())
    add_band_edges(wisp, clip, out);
  add_highlights(wisp, clip, style, out);
}

}  // namespace wisp::vector
