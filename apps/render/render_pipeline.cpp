// The per-frame pipeline (see render_pipeline.hpp).
#include "apps/render/render_pipeline.hpp"

#include "apps/render/body_hatching.hpp"

#include <algorithm>

#include "diffusion/antialias.hpp"
#include "diffusion/blur.hpp"
#include "diffusion/rasterize.hpp"
#include "diffusion/timer.hpp"
#include "vector/hair_base.hpp"
#include "vector/hair_curves.hpp"
#include "vector/polygon.hpp"

namespace wisp::render {
namespace {

using diffusion::Clock;
using diffusion::ms_since;

// Flat SVGs: each wisp's front region with its inside colours as a gradient from root to tip,
// read off its outline's stops: on the highlight side for Faraj's colour point (where the
// highlight is), averaged over both sides for lit shading (the light across the wisp is lost).
std::vector<FlatRegion> flat_regions(const std::vector<vector::Wisp>& wisps,
                                     const vector::WispArrangement& arrangement,
                                     const std::vector<diffusion::DiffusionCurve>& curves,
                                     const std::vector<int>& outline_of,
                                     const vector::HairStyle& style) {
  constexpr int kStops = 16;
  const bool lit = style.shading.model == vector::ShadingModel::Lit;
  std::vector<FlatRegion> out;
  for (size_t w = 0; w < wisps.size() && w < arrangement.front_regions.size(); ++w) {
    const int c = outline_of[w];
    if (arrangement.front_regions[w].polygons.empty() || c < 0) continue;
    const vector::Wisp& wisp = wisps[w];
    const std::vector<diffusion::ColorStop>& inside = curves[c].left;
    FlatRegion r;
    r.wisp = wisp.strand;
    r.area = arrangement.front_regions[w];
    r.from = wisp.centre.points.front();
    r.to = wisp.centre.points.back();
    std::vector<double> ts;
    for (int k = 0; k <= kStops; ++k) ts.push_back(double(k) / kStops);
    if (!lit) {  // the colour point's own places, so the highlight peak is not missed
      const double a = style.highlight_along, h = 0.5 * style.highlight_spread;
      for (double t : {a - h, a, a + h}) ts.push_back(std::clamp(t, 0.0, 1.0));
      std::sort(ts.begin(), ts.end());
    }
    for (double t : ts) {
      const auto colour = [&](bool left) {
        return diffusion::color_at(inside, vector::outline_parameter(wisp, t, left));
      };
      const diffusion::Color col = lit ? diffusion::Color(0.5f * (colour(true) + colour(false)))
                                       : colour(style.highlight_on_left);
      r.stops.push_back({t, col});
    }
    out.push_back(std::move(r));
  }
  return out;
}

// Mixes the two sides' colours in every hair pixel that a visible curve crosses, by area; pixels
// outside the hair mask do not count, since the mask clips the hair image with its own coverage.
diffusion::AntialiasStats antialias_hair(const std::vector<diffusion::DiffusionCurve>& curves,
                                         const FrameSolution& solved, FramePicture& pic) {
  diffusion::AntialiasRegion region;
  region.centres.assign(size_t(pic.width) * pic.height, 0);
  for (const vector::MaskPolygon& m : pic.mask.polygons) {
    region.rings.push_back(m.outer);
    region.rings.insert(region.rings.end(), m.holes.begin(), m.holes.end());
  }
  vector::fill_centres(region.centres, pic.width, pic.height, region.rings, std::uint8_t(1));
  return diffusion::antialias(curves, pic.width, pic.height, solved.colours, solved.window,
                              pic.hair.planes, pic.hair_window, &region);
}

// The colour solve's window around the curves (see render_solve).
constexpr int kWindowMargin = 8;
constexpr int kWindowAlign = 32;

// The planes of the window `to` from `channels` planes of the window `from` (either may be the
// whole image), 0 where `to` reaches outside `from`.
std::vector<float> window_planes(const std::vector<float>& planes, int channels,
                                 const diffusion::PixelWindow& from,
                                 const diffusion::PixelWindow& to) {
  const size_t n = from.pixel_count(), m = to.pixel_count();
  std::vector<float> out(channels * m, 0.0f);
  const int x0 = std::max(from.x, to.x), x1 = std::min(from.x + from.width, to.x + to.width);
  const int y0 = std::max(from.y, to.y), y1 = std::min(from.y + from.height, to.y + to.height);
  for (int c = 0; c < channels && x0 < x1; ++c)
    for (int y = y0; y < y1; ++y) {
      const float* row = &planes[c * n + size_t(y - from.y) * from.width + (x0 - from.x)];
      std::copy(row, row + (x1 - x0), &out[c * m + size_t(y - to.y) * to.width + (x0 - to.x)]);
    }
  return out;
}

}  // namespace

FrameResult render_geometry(const sim::ProjectedFrame& frame, BodyLayer body,
                            std::vector<vector::Occluder> occluders, vector::HairBase base,
                            const FrameSetup& setup) {
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
  arr.keep_faces = setup.keep_faces || vector::needs_visible_regions(setup.style);
  arr.front_regions = setup.flat_regions;
  arr.occluders = std::move(occluders);
  arr.base = std::move(base);
  r.arrangement = vector::build_arrangement(r.wisps, arr);
  r.time.arrangement = ms_since(t0);

  t0 = Clock::now();
  vector::HairCurves hc = vector::shade_hair(frame, r.wisps, r.arrangement, setup.style);
  r.curves = std::move(hc.curves);
  r.curve_stats = hc.stats;
  // The hair base: its own region under the wisps, after their curves (outline_of stays valid).
  const Rgb base_color = vector::base_color(setup.style);
  for (diffusion::DiffusionCurve& c :
       vector::base_curves(arr.base, r.arrangement.base_visible, base_color))
    r.curves.push_back(std::move(c)), ++r.base_curves;
  r.time.curves = ms_since(t0);

  FramePicture& pic = r.picture;
  pic.width = W;
  pic.height = H;
  pic.background = setup.background;
  pic.body = std::move(body.paths);
  pic.face = std::move(body.face);
  pic.fur = std::move(body.fur);
  pic.mask = r.arrangement.mask;
  pic.base = r.arrangement.base_region;
  pic.base_color = base_color;
  for (const vector::Wisp& w : r.wisps) pic.outlines.push_back({w.strand, {w.outline.points}});
  if (setup.flat_regions) {
    pic.flat = flat_regions(r.wisps, r.arrangement, r.curves, hc.outline_of, setup.style);
    for (vector::HighlightRing& h : hc.highlights)
      pic.highlights.push_back(
          {r.wisps[h.wisp].strand, std::move(h.ring), setup.style.specular.color});
  }
  if (setup.style.ink.enabled()) {
    t0 = Clock::now();
    r.ink = vector::ink_curves(r.wisps, r.arrangement, setup.style.ink, W, H);
    for (const vector::InkCurve& c : r.ink) {
      pic.ink.push_back(ink_stroke(c, c.width, setup.style.ink.color));
      pic.ink.back().kind = c.silhouette ? "silhouette" : "occlusion";
    }
    r.time.ink = ms_since(t0);
  }
  if (setup.style.hatching.enabled) {
    t0 = Clock::now();
    r.hatching = vector::hatch_hair(frame, r.wisps, r.arrangement, setup.style, W, H);
    for (const vector::HatchStroke& h : r.hatching) {
      pic.hatching.push_back(ink_stroke(h, h.width, setup.style.hatching.color));
      pic.hatching.back().kind = "hair";
    }
    r.body_hatching = hatch_body(body.projected, r.arrangement.mask, setup.style, W, H);
    for (const BodyHatch& h : r.body_hatching) {
      pic.hatching.push_back(h.stroke);
      pic.hatching.back().kind = "body";
    }
    r.time.hatching = ms_since(t0);
  }

  r.time.total = ms_since(t_start);
  return r;
}

void render_solve(FrameResult& r, const sim::ProjectedFrame& frame, const FrameSetup& setup,
                  const FrameSolution* warm_start, const sim::ProjectedFrame* neighbour) {
  const auto t_start = Clock::now();
  FramePicture& pic = r.picture;
  const int W = pic.width, H = pic.height;
  if (!r.curves.empty()) {
    // Only the pixels near the curves are solved: the hair is shown through its mask, and the
    // anti-aliasing takes a pixel's colours from inside the mask only, so the solution is never
    // seen farther than a pixel from a visible curve. The margin leaves room to spare; corners
    // on a 32-pixel lattice keep the window for a frame or a few while the hair sways, which
    // keeps the solver's setup incremental there.
    r.window = setup.whole_image_solve
                   ? diffusion::PixelWindow{0, 0, W, H}
                   : diffusion::curves_window(r.curves, W, H, kWindowMargin, kWindowAlign);
    const diffusion::PixelWindow& win = r.window;
    // Rasterized here rather than with the geometry: frames waiting to be shaded do not hold
    // their constraints (18 MB at 1024^2).
    auto t0 = Clock::now();
    r.problem = diffusion::rasterize(r.curves, win);
    r.time.rasterize = ms_since(t0);
    t0 = Clock::now();
    const bool warm = warm_start && warm_start->width == W && warm_start->height == H;
    // No pixel near a curve (the hair is out of the picture): nothing to solve.
    diffusion::Solution s;
    if (win.pixel_count() > 0)
      s = warm ? diffusion::solve_multigrid(
                     r.problem, setup.solver,
                     window_planes(warm_start->colours, 3, warm_start->window, win))
               : diffusion::solve_multigrid(r.problem, setup.solver);
    r.time.solve = ms_since(t0);
    r.solve = s.stats;
    // The constraints are done with (the inspector shows them), before the images below.
    if (!setup.keep_faces) r.problem = {};
    // The picture's image, which anti-aliasing changes; the plain solve stays beside it. Both
    // hold the window alone (the frame is black outside it): planes of the whole image were 12 MB
    // at 1024^2 to allocate, zero and copy every frame, in pages the allocator had returned.
    pic.hair = {win.width, win.height, s.planes};
    pic.hair_window = win;
    r.solution = {W, H, win, std::move(s.planes), {}};
    t0 = Clock::now();
    const std::vector<diffusion::DiffusionCurve> blurred = vector::blur_curves(
        frame, r.wisps, r.arrangement, setup.style.blur, {setup.lens, neighbour});
    if (!blurred.empty()) {
      // The whole image: the blur spreads the hair beyond its mask, where the map is read.
      const bool warm_blur = warm && !warm_start->blur.empty();
      diffusion::Solution b = diffusion::solve_blur_map(blurred, W, H, setup.solver,
                                                        warm_blur ? &warm_start->blur : nullptr);
      pic.blur = std::move(b.planes);
      r.solution.blur = pic.blur;
      r.time.blur = ms_since(t0);
    }
  }
  if (!setup.keep_faces) r.arrangement.view = {};
  r.time.total += ms_since(t_start);
}

void render_finish(FrameResult& r, const FrameSetup& setup, const FrameSolution& solved) {
  const auto t_start = Clock::now();
  FramePicture& pic = r.picture;
  if (!r.curves.empty()) {
    if (setup.antialias) {
      const auto t0 = Clock::now();
      r.antialias = antialias_hair(r.curves, solved, pic);
      r.time.antialias = ms_since(t0);
    }
    if (!pic.blur.empty()) {
      const auto t0 = Clock::now();
      pic.blurred_hair = reblur_hair(pic);
      r.time.blur += ms_since(t0);
    }
  }
  r.time.total += ms_since(t_start);
}

void render_shading(FrameResult& r, const sim::ProjectedFrame& frame, const FrameSetup& setup,
                    const FrameSolution* warm_start, const sim::ProjectedFrame* neighbour) {
  render_solve(r, frame, setup, warm_start, neighbour);
  render_finish(r, setup, r.solution);
}

FrameResult render_frame(const sim::ProjectedFrame& frame, BodyLayer body,
                         std::vector<vector::Occluder> occluders, vector::HairBase base,
                         const FrameSetup& setup, const FrameSolution* warm_start,
                         const sim::ProjectedFrame* neighbour) {
  FrameResult r =
      render_geometry(frame, std::move(body), std::move(occluders), std::move(base), setup);
  render_shading(r, frame, setup, warm_start, neighbour);
  return r;
}

}  // namespace wisp::render
