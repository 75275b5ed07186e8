// The per-frame pipeline (see render_pipeline.hpp).
#include "apps/render_pipeline.hpp"

#include <algorithm>
#include <chrono>

#include "diffusion/rasterize.hpp"
#include "vector/bezier.hpp"
#include "vector/hair_curves.hpp"

namespace wisp::apps {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The visible regions of each wisp for flat SVGs: the covered faces grouped by their front wisp,
// each filled with the wisp's colours as a linear gradient from root to tip.
std::vector<io::FlatRegion> flat_regions(const std::vector<vector::Wisp>& wisps,
                                         const vector::ArrangementView& view,
                                         const vector::HairStyle& style) {
  std::vector<io::FlatRegion> out;
  for (const vector::ViewFace& f : view.faces) {
    if (f.front < 0 || !f.in_view || f.outer.empty()) continue;
    const vector::Wisp& w = wisps[f.front];
    io::FlatRegion r;
    r.area.outer = f.outer;
    r.area.holes = f.holes;
    r.from = w.centre.points.front();
    r.to = w.centre.points.back();
    const double a = style.highlight_along, h = 0.5 * style.highlight_spread;
    r.stops = {{0.0, style.hair},
               {std::clamp(a - h, 0.0, 1.0), style.hair},
               {std::clamp(a, 0.0, 1.0), style.highlight},
               {std::clamp(a + h, 0.0, 1.0), style.hair},
               {1.0, style.hair}};
    out.push_back(std::move(r));
  }
  return out;
}

// A fitted ink curve as a picture stroke; its flattening (for tools that draw polylines) at the
// cubics' ends and thirds.
io::InkStroke ink_stroke(const vector::InkCurve& c, const vector::InkStyle& style) {
  io::InkStroke s;
  s.color = style.color;
  s.closed = c.closed;
  s.curve = c.points;
  s.curve_width = c.width;
  const int k = int(c.points.size() - 1) / 3;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < 3; ++j) {
      const double u = j / 3.0, sp = (i + u) / k;
      const vector::Cubic q{c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2],
                            c.points[3 * i + 3]};
      s.points.push_back(vector::eval(q, u));
      s.width.push_back(vector::width_at(c.width, sp));
    }
  if (!c.closed) {
    s.points.push_back(c.points.back());
    s.width.push_back(vector::width_at(c.width, 1.0));
  }
  return s;
}

}  // namespace

FrameResult render_frame(const sim::ProjectedFrame& frame, std::vector<io::BodyPolygon> body,
                         std::vector<vector::Occluder> occluders, const FrameSetup& setup,
                         const std::vector<float>* warm_start) {
  const auto t_start = Clock::now();
  FrameResult r;
  const int W = frame.width, H = frame.height;

  auto t0 = Clock::now();
  vector::WispStyle style = setup.style.geometry;
  style.trim_hidden = occluders.empty();
  r.wisps = vector::build_wisps(frame, style);
  r.time.wisps = ms_since(t0);

  t0 = Clock::now();
  vector::ArrangementOptions arr;
  arr.view = vector::image_rect(W, H);
  // Curves inside wisps are clipped to the arrangement's faces.
  arr.debug_view =
      setup.debug_view || setup.flat_regions || vector::needs_visible_regions(setup.style);
  arr.occluders = std::move(occluders);
  r.arrangement = vector::build_arrangement(r.wisps, arr);
  r.time.arrangement = ms_since(t0);

  t0 = Clock::now();
  vector::HairCurves hc = vector::shade_hair(frame, r.wisps, r.arrangement, setup.style);
  r.curves = std::move(hc.curves);
  r.curve_stats = hc.stats;
  r.time.curves = ms_since(t0);

  io::FramePicture& pic = r.picture;
  pic.width = W;
  pic.height = H;
  pic.background = setup.background;
  pic.body = std::move(body);
  pic.mask = r.arrangement.mask;
  for (const vector::Wisp& w : r.wisps) pic.outlines.push_back(w.outline.points);
  if (setup.flat_regions) pic.flat = flat_regions(r.wisps, r.arrangement.view, setup.style);
  if (setup.style.ink.enabled()) {
    t0 = Clock::now();
    r.ink = vector::ink_curves(r.wisps, r.arrangement, setup.style.ink, W, H);
    for (const vector::InkCurve& c : r.ink) pic.ink.push_back(ink_stroke(c, setup.style.ink));
    r.time.ink = ms_since(t0);
  }

  if (!r.curves.empty()) {
    t0 = Clock::now();
    r.problem = diffusion::rasterize(r.curves, W, H);
    r.time.rasterize = ms_since(t0);
    t0 = Clock::now();
    const bool warm = warm_start && warm_start->size() == r.problem.pixel_count() * 3;
    diffusion::Solution s =
        diffusion::solve_multigrid(r.problem, setup.solver, warm ? warm_start : nullptr);
    r.time.solve = ms_since(t0);
    r.solve = s.stats;
    pic.hair = {W, H, s.planes};
    r.solution = std::move(s.planes);
  }
  if (!setup.debug_view) r.arrangement.view = {};
  r.time.total = ms_since(t_start);
  return r;
}

}  // namespace wisp::apps
