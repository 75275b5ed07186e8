// Wisps as diffusion curves: their outlines in every style, then the curves inside them (see
// hair_curves.hpp).
#include "vector/hair_curves.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "vector/inner_curves.hpp"
#include "vector/visible_region.hpp"
#include "vector/wisp_chart.hpp"
#include "vector/wisp_shader.hpp"

namespace wisp::vector {

double outline_parameter(const Wisp& wisp, double t, bool left_side) {
  const Outline& o = wisp.outline;
  const int k = o.piece_count();
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

using diffusion::ColorStop;
using Eigen::Vector2d;
using Eigen::Vector3d;

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

// Faraj's colouring alone (no light, no highlights): hair_curves, with its outlines' indices.
HairCurves faraj_curves(const std::vector<Wisp>& wisps, const WispArrangement& arrangement,
                        const HairStyle& style) {
  HairCurves result;
  result.outline_of.assign(wisps.size(), -1);
  result.curves = hair_curves(wisps, arrangement.visible, style);
  result.stats.outlines = int(result.curves.size());
  int k = 0;  // hair_curves keeps the wisps with a visible interval, in order
  for (size_t w = 0; w < wisps.size() && w < arrangement.visible.size(); ++w)
    if (!arrangement.visible[w].empty()) result.outline_of[w] = k++;
  return result;
}

// The charts of the wisps that show (null for hidden ones) and their shading samples.
struct WispCharts {
  std::vector<std::unique_ptr<WispChart>> chart;
  std::vector<std::vector<double>> samples;
};

WispCharts visible_wisp_charts(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                               const WispArrangement& arrangement, const HairStyle& style) {
  std::unordered_map<int, const sim::ProjectedStrand*> strand_of;
  for (const sim::ProjectedStrand& s : frame.strands) strand_of[s.id] = &s;
  const int n = int(wisps.size());
  WispCharts out;
  out.chart.resize(n);
  out.samples.resize(n);
  for (int w = 0; w < n; ++w) {
    if (w >= int(arrangement.visible.size()) || arrangement.visible[w].empty()) continue;
    const auto it = strand_of.find(wisps[w].strand);
    if (it == strand_of.end())
      throw std::invalid_argument("wisp " + std::to_string(w) + ": no strand with id " +
                                  std::to_string(wisps[w].strand) + " in the frame");
    out.chart[w] = std::make_unique<WispChart>(wisps[w], *it->second, frame.eye);
    out.samples[w] = out.chart[w]->samples(style.shading.sample_px);
  }
  return out;
}

// Where each wisp shows, for the curves inside wisps; none when the style draws no such curves or
// no wisp shows. Those curves cannot be placed without the arrangement's faces: an arrangement
// built without them is the caller's mistake, reported rather than papered over by dropping the
// curves.
std::optional<VisibleRegions> visible_regions(const WispArrangement& arrangement,
                                              const WispCharts& charts, const HairStyle& style) {
  const bool any_shows =
      std::any_of(charts.chart.begin(), charts.chart.end(), [](const auto& c) { return bool(c); });
  if (!needs_visible_regions(style) || !any_shows) return std::nullopt;
  if (arrangement.view.faces.empty())
    throw std::logic_error(
        "shade_hair: the style draws curves inside wisps, which are clipped to the arrangement's "
        "faces; build the arrangement with ArrangementOptions::keep_faces");
  return VisibleRegions(arrangement.view, int(charts.chart.size()));
}

// A visible wisp's outline: its inside colours lit by the shader or Faraj's colour point, the
// shadow colour outside (the highlight colour where another wisp's highlight lies just beyond
// it, `cover`), active on its visible intervals.
diffusion::DiffusionCurve outline_curve(int w, const Wisp& wisp, const WispShader& shader,
                                        const std::vector<double>& samples,
                                        const std::vector<std::pair<double, double>>& visible,
                                        const HighlightCover* cover, const HairStyle& style) {
  diffusion::DiffusionCurve outline;
  outline.points = wisp.outline.points;
  outline.left = style.shading.model == ShadingModel::Lit ? outline_stops(wisp, shader, samples)
                                                          : faraj_stops(wisp, style);
  outline.right = cover ? cover->outside_stops(wisp, w, style.shadow, style.specular.color)
                        : std::vector<ColorStop>{{0.0, style.shadow}, {1.0, style.shadow}};
  outline.active = visible;
  return outline;
}

// The highlights' outlines in pixels.
std::vector<HighlightRing> highlight_rings(const WispCharts& charts,
                                           const std::vector<std::vector<ChartPolygon>>& shapes) {
  std::vector<HighlightRing> out;
  for (size_t w = 0; w < shapes.size(); ++w)
    for (const ChartPolygon& p : shapes[w]) {
      const WispChart& chart = *charts.chart[w];
      HighlightRing h{int(w), {}};
      for (const Vector2d& tu : highlight_outline(chart, charts.samples[w].size(), p))
        h.ring.push_back(chart.point(tu.x(), tu.y()));
      out.push_back(std::move(h));
    }
  return out;
}

// The highlights, each where its wisp shows, for the outlines in front of them; none without
// highlights or regions.
std::optional<HighlightCover> highlight_cover(const std::vector<HighlightRing>& rings,
                                              const std::optional<VisibleRegions>& regions) {
  if (!regions) return std::nullopt;
  std::optional<HighlightCover> cover;
  cover.emplace(*regions);
  for (const HighlightRing& h : rings) cover->add(h.wisp, h.ring);
  if (cover->empty()) return std::nullopt;
  return cover;
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

bool needs_visible_regions(const HairStyle& style) {
  return style.specular.shape != HighlightShape::None || style.hatching.enabled ||
         (style.shading.model == ShadingModel::Lit &&
          (style.shading.centre_line || (style.shading.ramp && style.shading.hard_bands)));
}

HairCurves shade_hair(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                      const WispArrangement& arrangement, const HairStyle& style) {
  const bool lit = style.shading.model == ShadingModel::Lit;
  if (!lit && style.specular.shape == HighlightShape::None)
    return faraj_curves(wisps, arrangement, style);

  const FrameLight light = frame_light(frame, wisps, style);
  std::optional<RampBands> bands;
  if (lit && style.shading.ramp)
    bands.emplace(*style.shading.ramp,
                  style.shading.hard_bands ? style.shading.band_threshold : 1e9);
  const WispCharts charts = visible_wisp_charts(frame, wisps, arrangement, style);
  const std::optional<VisibleRegions> regions = visible_regions(arrangement, charts, style);
  const std::vector<std::vector<ChartPolygon>> highlights =
      highlight_shapes(charts.chart, charts.samples, style, light, frame);

  // Outlines first, in wisp order, then the curves inside the wisps.
  HairCurves result;
  result.highlights = highlight_rings(charts, highlights);
  const std::optional<HighlightCover> cover = highlight_cover(result.highlights, regions);
  result.outline_of.assign(wisps.size(), -1);
  InnerCurves inner;
  for (int w = 0; w < int(wisps.size()); ++w) {
    if (!charts.chart[w]) continue;
    const WispShader shader(*charts.chart[w], style, light, bands ? &*bands : nullptr);
    result.outline_of[w] = int(result.curves.size());
    result.curves.push_back(outline_curve(w, wisps[w], shader, charts.samples[w],
                                          arrangement.visible[w], cover ? &*cover : nullptr,
                                          style));
    ++result.stats.outlines;
    if (regions)
      add_inner_curves({w, charts.chart[w].get(), &charts.samples[w], &shader, &highlights[w]},
                       *regions, style, inner);
  }
  for (auto& c : inner.curves) result.curves.push_back(std::move(c));
  result.stats.centre_lines = inner.centre_lines;
  result.stats.band_edges = inner.band_edges;
  result.stats.highlights = inner.highlights;
  return result;
}

}  // namespace wisp::vector
