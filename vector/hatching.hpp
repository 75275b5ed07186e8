// Pen hatching on the hair (Costigan 2013, section 4.3.8, after Praun et al.'s tonal art maps),
// as vector strokes. Costigan's viewport hatching swam over the moving hair (the "shower door");
// here every stroke is laid in its wisp's own coordinates: along, the arc length from the strand's
// root in scene units (of its 3D samples, so a stroke keeps its place on the strand while the
// strand moves), and across, the chart's u (vector/wisp_chart.hpp: -1 on the Right outline, +1 on
// the Left). The chart places such a point inside the wisp's band every frame.
//
// The tonal art map: each wisp has one ordered list of strokes, planned in blocks of kHatchBlock
// along the strand on a coverage grid of HatchStyle::lanes columns across and square cells
// along. Stroke by stroke, `candidates` random ones are tried and the one that darkens the grid
// most is kept (Costigan's "greatest tonal contribution"; a cell's tone is 1 - (1 - a)^n for n
// strokes over it); strokes join band 0 until the grid's mean tone reaches coverage[0], then band
// 1 up to coverage[1], and so on; the darkest band (with `cross`) adds strokes across the hair at
// cross_angle_deg instead. A stroke of band k is drawn where the shading's x (vector/
// wisp_shader.hpp) is below tones[k]: a lighter tone shows a prefix of a darker tone's list, the
// nesting that keeps strokes from popping as the light changes. Strokes are big by default (his
// users preferred big ones).
//
// Drawing: each stroke is sampled about every pixel along its image, cut exactly (bisection to
// 1e-4 px) where it leaves the wisp's visible region (vector/visible_region.hpp: the
// arrangement's faces whose front-most wisp it is), its tone band, or comes nearer the wisp's
// outline than half its width (so thin tips stay clear), fitted with cubics and given a
// width like ink: a pen's taper at its own ends, fading in over `soft` below its band's tone,
// tapering to 0 over `end_taper` px where it is clipped.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "diffusion/bezier.hpp"
#include "sim/projected.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_style.hpp"
#include "vector/wisp_chart.hpp"

namespace wisp::vector {

constexpr double kHatchBlock = 0.25;  // scene units of strand planned together

// One stroke of a wisp's ordered list, in the wisp's (along, across) coordinates.
struct PlannedStroke {
  Eigen::Vector2d from{0, 0}, to{0, 0};
  int band = 0;  // the lightest tone band whose prefix holds it
  bool cross = false;
};

// The ordered list of strand `strand` over along in [0, length): bands ascending, and within a
// band in the order chosen. `wisp_width`: the style's wisp width (scene units), the coverage
// grid's scale across. Depends only on these arguments (and on no frame): the same strokes every
// frame.
std::vector<PlannedStroke> plan_wisp_strokes(int strand, double length, double wisp_width,
                                             const HatchStyle& style);

// A wisp's (along, across) coordinates in pixels.
class HatchChart {
 public:
  // `strand`: the one the wisp was built from (its 3D samples give the arc length).
  HatchChart(const Wisp& wisp, const WispChart& chart, const sim::ProjectedStrand& strand);

  double length() const { return arc_.empty() ? 0 : arc_.back(); }
  // The chart's t at `along`; nothing beyond the part of the strand the wisp was built from.
  std::optional<double> chart_t(double along) const;
  // The along coordinates of the wisp's ends.
  std::pair<double, double> along_range() const;
  const WispChart& chart() const { return chart_; }
  std::optional<Eigen::Vector2d> point(double along, double across) const;

 private:
  const Wisp& wisp_;
  const WispChart& chart_;
  std::vector<double> arc_;  // arc length at each 3D sample
};

// A drawn piece of a stroke: a Bezier path with its full width as (s, px) stops, linear between.
struct HatchStroke : diffusion::BezierPath {
  std::vector<std::pair<double, double>> width;
  int wisp = -1;    // index into the frame's wisps
  int strand = -1;  // its sim::ProjectedStrand::id
  int rank = 0;     // in the wisp's ordered list
  int band = 0;
  bool cross = false;
  Eigen::Vector2d from{0, 0}, to{0, 0};  // the whole stroke in (along, across)
  double f0 = 0, f1 = 1;                 // the part of it drawn, as fractions from `from` to `to`
};

// The hatch strokes of every visible wisp, in wisp order. Needs the arrangement's faces
// (ArrangementOptions::keep_faces; std::logic_error without them when a wisp shows). Widths are
// HatchStyle::width scaled like ink (vector/ink_strokes.hpp: ink_scale). None unless enabled.
std::vector<HatchStroke> hatch_hair(const sim::ProjectedFrame& frame,
                                    const std::vector<Wisp>& wisps,
                                    const WispArrangement& arrangement, const HairStyle& style,
                                    int width, int height);

// The runs of a sampled path where a predicate holds, their ends moved onto where it flips:
// clips the hair's and the body's pen strokes to their regions. `samples` follow the path, each
// with a bool `on`; between(a, b, m) is the sample at fraction m of the way from a to b.
// Between neighbours that are both on, a sliver of what is off may still cut the path: the step
// is halved there while crosses(a, b) says the region's edge may pass between the two (it says
// no below the distance worth resolving). Each run's ends take edge_iterations(a, b) bisection
// steps between its last sample on one side and the first on the other.
template <class Sample, class Between, class Crosses, class EdgeIterations>
std::vector<std::vector<Sample>> runs_on(const std::vector<Sample>& samples, Between between,
                                         Crosses crosses, EdgeIterations edge_iterations) {
  std::vector<Sample> dense;
  const std::function<void(const Sample&, const Sample&)> refine = [&](const Sample& a,
                                                                       const Sample& b) {
    if (!crosses(a, b)) return;
    const Sample m = between(a, b, 0.5);
    refine(a, m);
    dense.push_back(m);
    if (m.on) refine(m, b);
  };
  for (size_t k = 0; k < samples.size(); ++k) {
    if (k > 0 && samples[k - 1].on && samples[k].on) refine(samples[k - 1], samples[k]);
    dense.push_back(samples[k]);
  }
  const auto edge = [&](const Sample& a, const Sample& b) {
    double lo = 0, hi = 1;
    for (int k = edge_iterations(a, b); k > 0; --k) {
      const double m = 0.5 * (lo + hi);
      (between(a, b, m).on == a.on ? lo : hi) = m;
    }
    return between(a, b, a.on ? lo : hi);  // the side that is on
  };
  std::vector<std::vector<Sample>> runs;
  for (size_t i = 0; i < dense.size();) {
    if (!dense[i].on) {
      ++i;
      continue;
    }
    std::vector<Sample>& run = runs.emplace_back();
    if (i > 0) run.push_back(edge(dense[i - 1], dense[i]));
    while (i < dense.size() && dense[i].on) run.push_back(dense[i++]);
    if (i < dense.size()) run.push_back(edge(dense[i - 1], dense[i]));
  }
  return runs;
}

// The width factor of a pen stroke at fraction f of its length: thin at both ends.
double pen_profile(double f);

// The factor by which a stroke of a band whose tone is `tone` shows at shading x: 0 at x >= tone,
// rising smoothly to 1 at x <= tone - soft.
double tone_gate(double x, double tone, double soft);

}  // namespace wisp::vector
