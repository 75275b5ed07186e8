// Hatch strokes on the hair (see hatching.hpp).
#include "vector/hatching.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "sim/rng.hpp"
#include "vector/ink_strokes.hpp"
#include "vector/stroke_fit.hpp"
#include "vector/visible_region.hpp"
#include "vector/wisp_shader.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

constexpr double kStrokeAlpha = 0.7;    // how much one stroke darkens a grid cell it crosses
constexpr double kFitTolerance = 0.05;  // px: fitted strokes against their exact samples
constexpr double kSampleStep = 1.0;     // px between a stroke's samples

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

// The coverage grid of one block: `along` cells of size h (scene units) by `lanes` columns
// across u in [-reach, reach].
class CoverageGrid {
 public:
  CoverageGrid(int along, int lanes, double h, double reach)
      : along_(along), lanes_(lanes), h_(h), reach_(reach), count_(size_t(along) * lanes, 0) {}

  // The cells a stroke in block coordinates crosses, each once.
  std::vector<int> cells(const PlannedStroke& s) const {
    std::vector<int> out;
    const Vector2d d = s.to - s.from;
    // Along is in scene units, across in u: step by half a cell in each.
    const double lane_u = 2 * reach_ / lanes_;
    const int n = std::max(
        1,
        int(std::ceil(std::max(std::abs(d.x()) / (0.5 * h_), std::abs(d.y()) / (0.5 * lane_u)))));
    for (int i = 0; i <= n; ++i) {
      const Vector2d p = s.from + d * (double(i) / n);
      const int a = int(std::floor(p.x() / h_));
      const int l = std::clamp(int(std::floor((p.y() + reach_) / lane_u)), 0, lanes_ - 1);
      if (a < 0 || a >= along_) continue;
      const int c = a * lanes_ + l;
      if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
    }
    return out;
  }
  // The rise of the grid's summed tone if the stroke over `cells` were added.
  double gain(const std::vector<int>& cells) const {
    double g = 0;
    for (int c : cells) g += std::pow(1 - kStrokeAlpha, count_[c]) * kStrokeAlpha;
    return g;
  }
  void add(const std::vector<int>& cells) {
    for (int c : cells) ++count_[c];
  }
  int size() const { return int(count_.size()); }

 private:
  int along_, lanes_;
  double h_, reach_;
  std::vector<int> count_;
};

// Random candidates of a family, in block coordinates [0, block) along.
PlannedStroke candidate(sim::Rng& rng, bool cross, double wisp_width, const HatchStyle& st) {
  PlannedStroke s;
  s.cross = cross;
  if (cross) {
    // From one side to the other at cross_angle_deg to the hair: across is u * wisp_width / 2
    // in scene units.
    const double extent = st.reach * wisp_width / std::tan(st.cross_angle_deg * M_PI / 180.0);
    const double a = rng.uniform(-0.5 * extent, kHatchBlock - 0.5 * extent);
    s.from = {a, -st.reach};
    s.to = {a + extent, st.reach};
  } else {
    const double len = st.length * (1 + st.length_jitter * rng.uniform(-1, 1));
    const double a = rng.uniform(-0.5 * len, kHatchBlock - 0.5 * len);
    const double u = rng.uniform(-st.reach, st.reach);
    const double drift = rng.uniform(-1, 1) * st.reach / st.lanes;  // half a lane either way
    s.from = {a, u};
    s.to = {a + len, std::clamp(u + drift, -st.reach, st.reach)};
  }
  return s;
}

std::uint64_t block_seed(std::uint64_t seed, int strand, int block) {
  sim::Rng mix(seed ^ (std::uint64_t(std::uint32_t(strand)) << 32) ^ std::uint64_t(block));
  mix.next();
  return mix.next();
}

}  // namespace

double pen_profile(double f) {
  return 0.2 + 0.8 * smoothstep(std::min(f, 1 - f) / 0.2);
}

double tone_gate(double x, double tone, double soft) {
  if (x >= tone) return 0;
  return soft > 0 ? smoothstep((tone - x) / soft) : 1.0;
}

std::vector<PlannedStroke> plan_wisp_strokes(int strand, double length, double wisp_width,
                                             const HatchStyle& st) {
  const int bands = int(std::min(st.tones.size(), st.coverage.size()));
  std::vector<std::vector<PlannedStroke>> by_band(bands);
  if (!(length > 0) || !(wisp_width > 0) || bands == 0) return {};
  const double h = st.reach * wisp_width / st.lanes;  // a lane's width in scene units
  const int along = std::max(1, int(std::ceil(kHatchBlock / h)));
  const int blocks = int(std::ceil(length / kHatchBlock));
  for (int b = 0; b < blocks; ++b) {
    sim::Rng rng(block_seed(st.seed, strand, b));
    CoverageGrid grid(along, st.lanes, h, st.reach);
    double tone = 0;
    for (int k = 0; k < bands; ++k) {
      const bool cross = st.cross && bands >= 2 && k == bands - 1;
      // A guard against a target the grid cannot reach (coverage is at most 0.9).
      for (int guard = 0; tone < st.coverage[k] * grid.size() && guard < 4 * grid.size(); ++guard) {
        PlannedStroke best;
        std::vector<int> best_cells;
        double best_gain = -1;
        for (int c = 0; c < st.candidates; ++c) {
          const PlannedStroke s = candidate(rng, cross, wisp_width, st);
          std::vector<int> cells = grid.cells(s);
          const double g = grid.gain(cells);
          if (g > best_gain) best = s, best_cells = std::move(cells), best_gain = g;
        }
        if (best_gain <= 0) continue;
        grid.add(best_cells);
        tone += best_gain;
        best.band = k;
        best.from.x() += b * kHatchBlock;
        best.to.x() += b * kHatchBlock;
        by_band[k].push_back(best);
      }
    }
  }
  std::vector<PlannedStroke> out;
  for (const auto& list : by_band) out.insert(out.end(), list.begin(), list.end());
  return out;
}

HatchChart::HatchChart(const Wisp& wisp, const WispChart& chart, const sim::ProjectedStrand& strand)
    : wisp_(wisp), chart_(chart) {
  arc_.reserve(strand.world.size());
  for (size_t i = 0; i < strand.world.size(); ++i)
    arc_.push_back(i == 0 ? 0.0 : arc_.back() + (strand.world[i] - strand.world[i - 1]).norm());
}

std::optional<double> HatchChart::chart_t(double along) const {
  const int n = int(arc_.size());
  if (n < 2 || along < 0 || along > arc_.back()) return std::nullopt;
  // Along -> the strand parameter (sample index over samples - 1) ...
  const int i = std::clamp(
      int(std::upper_bound(arc_.begin(), arc_.end(), along) - arc_.begin()) - 1, 0, n - 2);
  const double seg = arc_[i + 1] - arc_[i];
  const double v = (i + (seg > 0 ? (along - arc_[i]) / seg : 0.0)) / (n - 1);
  // ... -> the centre spline's t, through its strand parameter per control point.
  const std::vector<double>& su = wisp_.centre.strand_u;
  const int m = int(su.size());
  if (m < 2 || v < su.front() || v > su.back()) return std::nullopt;
  const int j =
      std::clamp(int(std::upper_bound(su.begin(), su.end(), v) - su.begin()) - 1, 0, m - 2);
  const double d = su[j + 1] - su[j];
  return (j + (d > 0 ? (v - su[j]) / d : 0.0)) / (m - 1);
}

std::pair<double, double> HatchChart::along_range() const {
  const std::vector<double>& su = wisp_.centre.strand_u;
  const int n = int(arc_.size());
  if (su.empty() || n < 2) return {0, 0};
  const auto arc_at = [&](double v) {
    const double x = std::clamp(v, 0.0, 1.0) * (n - 1);
    const int i = std::clamp(int(x), 0, n - 2);
    return arc_[i] + (x - i) * (arc_[i + 1] - arc_[i]);
  };
  return {arc_at(su.front()), arc_at(su.back())};
}

std::optional<Vector2d> HatchChart::point(double along, double across) const {
  const std::optional<double> t = chart_t(along);
  if (!t) return std::nullopt;
  return chart_.point(*t, across);
}

namespace {

// Draws one planned stroke of wisp w: its pieces where it shows and its band's tone holds.
void draw_stroke(const PlannedStroke& s, int w, int strand, int rank, const HatchChart& hc,
                 const WispShader& shader, const VisibleRegions& regions, const HatchStyle& st,
                 double full_width, double taper_px, std::vector<HatchStroke>& out) {
  const double tone = st.tones[s.band];
  const auto tu = [&](double f) { return Vector2d(s.from + f * (s.to - s.from)); };
  struct Sample {
    double f = 0;
    Vector2d p{0, 0};
    double x = 1;  // the shading's x
    bool on = false;
  };
  const auto sample = [&](double f) {
    Sample r;
    r.f = f;
    const Vector2d q = tu(f);
    const std::optional<double> t = hc.chart_t(q.x());
    if (!t) return r;
    r.p = hc.point(q.x(), q.y()).value();
    r.x = shader.x(*t, q.y());
    // Half the stroke's width from the wisp's side at least, so no ink crosses its outline (and
    // none crowds into its thin tip).
    const double side =
        (hc.chart().point(*t, q.y() >= 0 ? 1 : -1) - hc.chart().point(*t, 0)).norm();
    r.on =
        r.x < tone && side * (1 - std::abs(q.y())) >= 0.5 * full_width && regions.contains(w, r.p);
    return r;
  };
  // The part of the stroke on the wisp (along is linear in f), and its length on screen from a
  // coarse pass.
  const auto [a0, a1] = hc.along_range();
  const double da = s.to.x() - s.from.x();
  double fa = 0, fb = 1;
  if (da != 0) {
    const double ga = (a0 - s.from.x()) / da, gb = (a1 - s.from.x()) / da;
    fa = std::max(0.0, std::min(ga, gb));
    fb = std::min(1.0, std::max(ga, gb));
  }
  if (!(fb > fa)) return;
  constexpr int kCoarse = 16;
  double len = 0, longest = 0;
  std::optional<Vector2d> prev;
  for (int i = 0; i <= kCoarse; ++i) {
    const Vector2d q = tu(fa + (fb - fa) * i / kCoarse);
    const std::optional<Vector2d> p = hc.point(q.x(), q.y());
    if (p && prev) {
      len += (*p - *prev).norm();
      longest = std::max(longest, (*p - *prev).norm());
    }
    prev = p;
  }
  if (len < 1) return;
  // At most kSampleStep apart where the coarse pass found the image stretched most.
  const int n = std::clamp(kCoarse * int(std::ceil(longest / kSampleStep)), kCoarse, 8192);
  std::vector<Sample> samples;
  samples.reserve(n + 1);
  for (int i = 0; i <= n; ++i) samples.push_back(sample(fa + (fb - fa) * i / n));
  const auto between = [&](const Sample& a, const Sample& b, double m) {
    return sample((1 - m) * a.f + m * b.f);
  };
  // A sliver of another wisp may cross the stroke between two samples that are on.
  const auto crosses = [&](const Sample& a, const Sample& b) {
    return (b.p - a.p).norm() >= 1e-3 && regions.crosses(w, a.p, b.p);
  };
  // Where `on` flips: bisection to 1e-4 of the stroke... or finer.
  const int iterations =
      std::clamp(int(std::ceil(std::log2(std::max(1.0, longest * kCoarse / n / 1e-4)))), 8, 30);
  for (const std::vector<Sample>& run : runs_on(
           samples, between, crosses, [&](const Sample&, const Sample&) { return iterations; })) {
    if (run.size() < 2) continue;
    std::vector<Vector2d> pts;
    std::vector<double> arc = {0};
    for (const Sample& r : run) {
      if (!pts.empty()) arc.push_back(arc.back() + (r.p - pts.back()).norm());
      pts.push_back(r.p);
    }
    const double run_len = arc.back();
    if (run_len < 0.5) continue;
    // Clipped ends (not the stroke's own) taper to 0.
    const bool cut_start = run.front().f > 0, cut_end = run.back().f < 1;
    std::vector<double> widths;
    for (size_t k = 0; k < run.size(); ++k) {
      double wk = full_width * pen_profile(run[k].f) * tone_gate(run[k].x, tone, st.soft);
      if (taper_px > 0) {
        if (cut_start) wk *= smoothstep(arc[k] / taper_px);
        if (cut_end) wk *= smoothstep((run_len - arc[k]) / taper_px);
      }
      widths.push_back(wk);
    }
    FitOptions fit;
    fit.tolerance = kFitTolerance;
    const FittedPath path = fit_cubics(pts, fit);
    if (path.piece_count() == 0) continue;
    HatchStroke h;
    h.points = path.points;
    for (size_t k = 0; k < pts.size(); ++k) h.width.emplace_back(path.param[k], widths[k]);
    h.wisp = w;
    h.strand = strand;
    h.rank = rank;
    h.band = s.band;
    h.cross = s.cross;
    h.from = s.from;
    h.to = s.to;
    h.f0 = run.front().f;
    h.f1 = run.back().f;
    out.push_back(std::move(h));
  }
}

}  // namespace

std::vector<HatchStroke> hatch_hair(const sim::ProjectedFrame& frame,
                                    const std::vector<Wisp>& wisps,
                                    const WispArrangement& arrangement, const HairStyle& style,
                                    int width, int height) {
  std::vector<HatchStroke> out;
  const HatchStyle& st = style.hatching;
  if (!st.enabled) return out;
  const int n = int(wisps.size());
  const auto shows = [&](int w) {
    return w < int(arrangement.visible.size()) && !arrangement.visible[w].empty();
  };
  bool any = false;
  for (int w = 0; w < n && !any; ++w) any = shows(w);
  if (!any) return out;
  if (arrangement.view.faces.empty())
    throw std::logic_error(
        "hatch_hair: strokes are clipped to the arrangement's faces; build the arrangement with "
        "ArrangementOptions::keep_faces");
  const VisibleRegions regions(arrangement.view, n);
  const FrameLight light = frame_light(frame, wisps, style);
  const double scale = ink_scale(style.ink, width, height);
  std::unordered_map<int, const sim::ProjectedStrand*> strand_of;
  for (const sim::ProjectedStrand& s : frame.strands) strand_of[s.id] = &s;
  for (int w = 0; w < n; ++w) {
    if (!shows(w)) continue;
    const auto it = strand_of.find(wisps[w].strand);
    if (it == strand_of.end())
      throw std::invalid_argument("wisp " + std::to_string(w) + ": no strand with id " +
                                  std::to_string(wisps[w].strand) + " in the frame");
    const WispChart chart(wisps[w], *it->second, frame.eye);
    const WispShader shader(chart, style, light, nullptr);
    const HatchChart hc(wisps[w], chart, *it->second);
    const std::vector<PlannedStroke> plan =
        plan_wisp_strokes(wisps[w].strand, hc.length(), style.geometry.width, st);
    for (size_t r = 0; r < plan.size(); ++r)
      draw_stroke(plan[r], w, wisps[w].strand, int(r), hc, shader, regions, st, st.width * scale,
                  st.end_taper * scale, out);
  }
  return out;
}

}  // namespace wisp::vector
