// Wisps as diffusion curves: Faraj's colouring and every other style (see hair_curves.hpp).
#include "vector/hair_curves.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "vector/chart_contour.hpp"
#include "vector/highlights.hpp"
#include "vector/polygon.hpp"
#include "vector/stroke_fit.hpp"
#include "vector/visible_region.hpp"
#include "vector/wisp_chart.hpp"
#include "vector/wisp_shader.hpp"

namespace wisp::vector {

double outline_parameter(const Wisp& wisp, double t, bool left_side) {
  const Outline& o = wisp.outline;
  const int k = o.cubic_count();
  const Side wanted = left_side ? Side::Left : Side::Right;
  // Along a side the centre parameter is monotonic: increasing on the left, decreasing on the
  // right. Find the cubic whose end points bracket t and interpolate linearly between them.
  double best_s = -1, best_gap = 1e18;
  for (int i = 0; i < k; ++i) {
    if (o.side[i] != wanted) continue;
    const double t0 = o.t[3 * i], t1 = o.t[3 * i + 3];
    const double lo = std::min(t0, t1), hi = std::max(t0, t1);
    if (t >= lo && t <= hi) {
      const double f = hi > lo ? (t - t0) / (t1 - t0) : 0.0;
      return (i + f) / k;
    }
    const double gap = std::min(std::abs(t - t0), std::abs(t - t1));
    if (gap < best_gap) {
      best_gap = gap;
      best_s = (std::abs(t - t0) < std::abs(t - t1) ? i : i + 1) / double(k);
    }
  }
  return std::clamp(best_s, 0.0, 1.0);
}

namespace {

// Faraj's colour point: the highlight colour at one place along one side, fading back to the
// hair colour on both sides of it (the inside stops of every outline in the faraj style).
std::vector<diffusion::ColorStop> faraj_stops(const Wisp& wisp, const HairStyle& style) {
  const bool left = style.highlight_on_left;
  const double a = style.highlight_along, h = 0.5 * style.highlight_spread;
  double s[3] = {outline_parameter(wisp, std::clamp(a - h, 0.0, 1.0), left),
                 outline_parameter(wisp, a, left),
                 outline_parameter(wisp, std::clamp(a + h, 0.0, 1.0), left)};
  std::sort(s, s + 3);
  return {{0.0, style.hair},
          {s[0], style.hair},
          {s[1], style.highlight},
          {s[2], style.hair},
          {1.0, style.hair}};
}

}  // namespace

std::vector<diffusion::DiffusionCurve> hair_curves(
    const std::vector<Wisp>& wisps,
    const std::vector<std::vector<std::pair<double, double>>>& visible, const HairStyle& style) {
  std::vector<diffusion::DiffusionCurve> out;
  out.reserve(wisps.size());
  for (size_t w = 0; w < wisps.size(); ++w) {
    // A wholly hidden wisp constrains nothing (an empty active set would mean "everywhere").
    if (w >= visible.size() || visible[w].empty()) continue;
    const Wisp& wisp = wisps[w];
    diffusion::DiffusionCurve c;
    c.points = wisp.outline.points;
    c.left = faraj_stops(wisp, style);
    c.right = {{0.0, style.shadow}, {1.0, style.shadow}};
    c.active = visible[w];
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace wisp::vector

// ---------------------------------------------------------------------------------------------
// Every style: lit outlines, centre lines, band edges and highlights.

namespace wisp::vector {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
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

// Colour stops along a curve through chart points `tu` at parameters `s`: the shader's colour
// at each point, and where the ramp's band changes between two points, a pair of stops at the
// band edge with the colours of both bands (a sharp step).
std::vector<ColorStop> stops_along(const WispShader& sh, const std::vector<Vector2d>& tu,
                                   const std::vector<double>& s) {
  std::vector<ColorStop> out;
  const RampBands* bands = sh.bands();
  int prev_band = 0;
  for (size_t i = 0; i < tu.size(); ++i) {
    const int b = sh.band(tu[i].x(), tu[i].y());
    if (i > 0 && bands && b != prev_band) {
      // Each edge between the two bands, in the order the segment crosses them.
      const int step = b > prev_band ? 1 : -1;
      double lo_f = 0;
      for (int from = prev_band; from != b; from += step) {
        const double edge = bands->edges()[step > 0 ? from : from - 1];
        double lo = lo_f, hi = 1;
        const auto x_at = [&](double f) {
          const Vector2d p = tu[i - 1] + f * (tu[i] - tu[i - 1]);
          return sh.x(p.x(), p.y());
        };
        const bool rising = step > 0;
        for (int k = 0; k < 16; ++k) {
          const double m = 0.5 * (lo + hi);
          ((x_at(m) < edge) == rising ? lo : hi) = m;
        }
        const double f = 0.5 * (lo + hi);
        lo_f = f;
        const Vector2d p = tu[i - 1] + f * (tu[i] - tu[i - 1]);
        const double sc = s[i - 1] + f * (s[i] - s[i - 1]);
        out.push_back({sc, sh.color_in_band(p.x(), p.y(), from)});
        out.push_back({sc, sh.color_in_band(p.x(), p.y(), from + step)});
      }
    }
    out.push_back({s[i], sh.color_in_band(tu[i].x(), tu[i].y(), b)});
    prev_band = b;
  }
  for (size_t i = 1; i < out.size(); ++i) out[i].t = std::max(out[i].t, out[i - 1].t);
  return out;
}

// The inside colours of a lit wisp's outline: its Left side (u = +1) root to tip, the tip cap,
// its Right side (u = -1) tip to root, the root cap back to the start.
std::vector<ColorStop> outline_stops(const Wisp& wisp, const WispShader& sh,
                                     const std::vector<double>& ts) {
  std::vector<Vector2d> tu;
  std::vector<double> s;
  for (double t : ts) {
    tu.emplace_back(t, 1.0);
    s.push_back(outline_parameter(wisp, t, true));
  }
  for (auto it = ts.rbegin(); it != ts.rend(); ++it) {
    tu.emplace_back(*it, -1.0);
    s.push_back(outline_parameter(wisp, *it, false));
  }
  tu.emplace_back(ts.front(), 1.0);
  s.push_back(1.0);
  s.front() = 0.0;
  for (size_t i = 1; i < s.size(); ++i) s[i] = std::max(s[i], s[i - 1]);
  return stops_along(sh, tu, s);
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

}  // namespace

bool needs_visible_regions(const HairStyle& style) {
  return style.specular.shape != HighlightShape::None ||
         (style.shading.model == ShadingModel::Lit &&
          (style.shading.centre_line || (style.shading.ramp && style.shading.hard_bands)));
}

HairCurves shade_hair(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                      const WispArrangement& arrangement, const HairStyle& style) {
  HairCurves result;
  result.outline_of.assign(wisps.size(), -1);
  const bool lit = style.shading.model == ShadingModel::Lit;
  const HighlightShape shape = style.specular.shape;
  if (!lit && shape == HighlightShape::None) {
    result.curves = hair_curves(wisps, arrangement.visible, style);
    result.stats.outlines = int(result.curves.size());
    int k = 0;  // hair_curves keeps the wisps with a visible interval, in order
    for (size_t w = 0; w < wisps.size() && w < arrangement.visible.size(); ++w)
      if (!arrangement.visible[w].empty()) result.outline_of[w] = k++;
    return result;
  }

  // What the wisps share: the light, the depth range, the head's centre, the ramp's bands.
  std::unordered_map<int, const sim::ProjectedStrand*> strand_of;
  std::vector<Vector3d> roots;
  for (const sim::ProjectedStrand& s : frame.strands) {
    strand_of[s.id] = &s;
    if (!s.world.empty()) roots.push_back(s.world.front());
  }
  const Vector3d head_centre = head_centre_from_roots(roots);
  FrameLight light;
  light.head_centre = head_centre;
  light.light =
      frame.light_dir.norm() > 0 ? Vector3d(frame.light_dir.normalized()) : Vector3d::UnitZ();
  double zmin = 1e300, zmax = 0;
  for (const Wisp& w : wisps)
    for (double z : w.centre.depth) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
  light.z_near = style.shading.depth_near > 0 ? style.shading.depth_near : zmin;
  light.z_far = style.shading.depth_far > 0 ? style.shading.depth_far : zmax;
  std::optional<RampBands> bands;
  if (lit && style.shading.ramp)
    bands.emplace(*style.shading.ramp,
                  style.shading.hard_bands ? style.shading.band_threshold : 1e9);

  const bool regions_known = !arrangement.view.faces.empty();
  std::optional<VisibleRegions> regions;
  if (regions_known) regions.emplace(arrangement.view, int(wisps.size()));

  // Charts and shading samples of the wisps that show.
  const int n = int(wisps.size());
  std::vector<std::unique_ptr<WispChart>> charts(n);
  std::vector<std::vector<double>> samples(n);
  for (int w = 0; w < n; ++w) {
    if (w >= int(arrangement.visible.size()) || arrangement.visible[w].empty()) continue;
    const auto it = strand_of.find(wisps[w].strand);
    if (it == strand_of.end())
      throw std::invalid_argument("wisp " + std::to_string(w) + ": no strand with id " +
                                  std::to_string(wisps[w].strand) + " in the frame");
    charts[w] = std::make_unique<WispChart>(wisps[w], *it->second, frame.eye);
    samples[w] = charts[w]->samples(style.shading.sample_px);
  }

  // Highlight shapes per wisp, in chart coordinates.
  std::vector<std::vector<ChartPolygon>> highlights(n);
  if (shape == HighlightShape::Band) {
    for (int w = 0; w < n; ++w)
      if (charts[w])
        highlights[w] = band_highlights(*charts[w], samples[w], style.specular, light.light);
  } else if (shape == HighlightShape::Anime) {
    double radius = 0;
    for (const Vector3d& r : roots) radius += (r - head_centre).norm() / double(roots.size());
    const AnimeBand band =
        anime_band(style.specular, frame, head_centre, radius, style.geometry.width);
    for (int w = 0; w < n; ++w)
      if (charts[w]) highlights[w] = anime_highlights(*charts[w], samples[w], style.specular, band);
  }

  // The highlights in pixels, for the outlines in front of them (HighlightCover).
  const auto step_t_of = [&](int w) {
    return (charts[w]->t_end() - charts[w]->t_begin()) / std::max<size_t>(8, samples[w].size());
  };
  std::optional<HighlightCover> cover;
  if (regions) {
    cover.emplace(*regions);
    for (int w = 0; w < n; ++w)
      for (const ChartPolygon& p : highlights[w]) {
        std::vector<Vector2d> ring;
        for (const Vector2d& tu : densify(p, step_t_of(w), 0.1))
          ring.push_back(charts[w]->point(tu.x(), tu.y()));
        cover->add(w, std::move(ring));
      }
  }

  std::vector<diffusion::DiffusionCurve> inner;
  for (int w = 0; w < n; ++w) {
    if (!charts[w]) continue;
    const Wisp& wisp = wisps[w];
    const WispChart& chart = *charts[w];
    const std::vector<double>& ts = samples[w];
    const WispShader shader(chart, style, light, bands ? &*bands : nullptr);

    diffusion::DiffusionCurve outline;
    outline.points = wisp.outline.points;
    outline.left = lit ? outline_stops(wisp, shader, ts) : faraj_stops(wisp, style);
    outline.right = cover ? cover->outside_stops(wisp, w, style.shadow, style.specular.color)
                          : std::vector<ColorStop>{{0.0, style.shadow}, {1.0, style.shadow}};
    outline.active = arrangement.visible[w];
    result.outline_of[w] = int(result.curves.size());
    result.curves.push_back(std::move(outline));
    ++result.stats.outlines;
    if (!regions) continue;

    const auto& shapes = highlights[w];
    const auto in_highlight = [&](const Vector2d& tu) {
      for (const ChartPolygon& p : shapes)
        if (inside_polygon(p, tu)) return true;
      return false;
    };
    const auto active = [&](const ChartCurve& c) {
      Intervals a = regions->active(w, c.path.points);
      if (!shapes.empty()) a = intersect_intervals(a, outside_of(c.tu, c.path.param, in_highlight));
      return a;
    };

    if (lit && style.shading.centre_line) {
      std::vector<Vector2d> tu;
      for (double t : ts) tu.emplace_back(t, 0.0);
      ChartCurve c = fit_chart_curve(chart, std::move(tu), false);
      if (c.path.cubic_count() > 0) {
        diffusion::DiffusionCurve d;
        d.points = c.path.points;
        d.left = stops_along(shader, c.tu, c.path.param);
        d.right = d.left;
        d.active = active(c);
        if (!d.active.empty()) inner.push_back(std::move(d)), ++result.stats.centre_lines;
      }
    }

    if (lit && bands && style.shading.hard_bands && !bands->edges().empty()) {
      ChartGrid g;
      g.t = ts;
      const int nu = 17;
      for (int j = 0; j < nu; ++j) g.u.push_back(-1.0 + 2.0 * j / (nu - 1));
      g.value.resize(g.t.size() * nu);
      for (size_t i = 0; i < g.t.size(); ++i)
        for (int j = 0; j < nu; ++j) g.value[i * nu + j] = shader.x(g.t[i], g.u[j]);
      const auto exact = [&](double t, double u) { return shader.x(t, u); };
      for (size_t e = 0; e < bands->edges().size(); ++e) {
        for (ChartContour& k : chart_contours(g, bands->edges()[e], exact)) {
          ChartCurve c = fit_chart_curve(chart, std::move(k.tu), k.closed);
          if (c.path.cubic_count() == 0) continue;
          diffusion::DiffusionCurve d;
          d.points = c.path.points;
          // Higher x lies on the chart's left, which is diffusion's right.
          for (size_t i = 0; i < c.tu.size(); ++i) {
            const double t = c.tu[i].x(), u = c.tu[i].y(), s = c.path.param[i];
            d.left.push_back({s, shader.color_in_band(t, u, int(e))});
            d.right.push_back({s, shader.color_in_band(t, u, int(e) + 1)});
          }
          if (k.closed) {
            // A loop starts at its sharpest corner: order the stops along the path and close.
            for (auto* side : {&d.left, &d.right}) {
              std::stable_sort(side->begin(), side->end(),
                               [](const ColorStop& a, const ColorStop& b) { return a.t < b.t; });
              side->push_back({1.0, side->front().color});
            }
            d.active = regions->active(w, d.points);
          } else {
            d.active = active(c);
          }
          if (!d.active.empty()) inner.push_back(std::move(d)), ++result.stats.band_edges;
        }
      }
    }

    for (const ChartPolygon& p : shapes) {
      ChartCurve c = fit_chart_curve(chart, densify(p, step_t_of(w), 0.1), true);
      if (c.path.cubic_count() == 0) continue;
      diffusion::DiffusionCurve d;
      d.points = c.path.points;
      // Counter-clockwise in the chart: the inside is on diffusion's right.
      d.right = {{0.0, style.specular.color}, {1.0, style.specular.color}};
      d.left_boundary = diffusion::Boundary::Neumann;
      d.active = regions->active(w, d.points);
      if (!d.active.empty()) inner.push_back(std::move(d)), ++result.stats.highlights;
    }
  }
  for (auto& c : inner) result.curves.push_back(std::move(c));
  return result;
}

}  // namespace wisp::vector
