// Wisps as diffusion curves. Each wisp's closed outline becomes one DiffusionCurve whose inside
// (diffusion's left: the outline turns counter-clockwise in (x, y)) carries the wisp's colours
// and whose outside carries the shadow colour, constrained only on the outline's visible
// intervals (from the arrangement).
//
// hair_curves: Faraj's colouring (the hair colour inside with one colour point, shadow outside).
// shade_hair: every style. With lit shading the inside colours come from the light on the wisp
// as a tube (vector/wisp_shader.hpp) at the outline (u = +-1); after the outlines come the curves
// inside the wisps that carry what diffusion from the outline alone cannot: centre lines, toon
// band edges and highlights (vector/inner_curves.hpp), active only where their wisp is visible. An
// outline in front of another wisp's highlight carries the highlight colour outside instead of
// the shadow colour, so a highlight band runs crisply from one wisp to the next.
#pragma once

#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "sim/projected.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_style.hpp"

namespace wisp::vector {

// The outline parameter s in [0,1] where the outline passes centre parameter t on the wisp's
// left side (root -> tip, the first half of the outline) or its right side (tip -> root).
double outline_parameter(const Wisp& wisp, double t, bool left_side);

// One curve per wisp that has a visible interval, in wisp order; `visible[i]` (the
// arrangement's intervals for wisp i) becomes the curve's active set.
std::vector<diffusion::DiffusionCurve> hair_curves(
    const std::vector<Wisp>& wisps,
    const std::vector<std::vector<std::pair<double, double>>>& visible, const HairStyle& style);

// Whether the style draws curves inside wisps; those need the arrangement's faces
// (ArrangementOptions::keep_faces) to be clipped to where their wisp shows.
bool needs_visible_regions(const HairStyle& style);

struct HairCurveStats {
  int outlines = 0, centre_lines = 0, band_edges = 0, highlights = 0;
};

// A highlight's outline in pixels; it shows where its wisp is visible.
struct HighlightRing {
  int wisp = -1;  // index into the wisps
  std::vector<Eigen::Vector2d> ring;
};

struct HairCurves {
  std::vector<diffusion::DiffusionCurve> curves;  // outlines first (wisp order), then the rest
  std::vector<HighlightRing> highlights;          // the highlights' shapes (as vector art)
  std::vector<int> outline_of;  // per wisp: the index of its outline in `curves`, or -1
  HairCurveStats stats;
};

// All the diffusion curves of a frame in the given style. `frame` supplies the light, the eye and
// the strands' 3D samples (by ProjectedStrand::id == Wisp::strand). Throws std::logic_error when
// the style draws curves inside wisps (needs_visible_regions) and a wisp shows but the
// arrangement was built without its faces.
HairCurves shade_hair(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                      const WispArrangement& arrangement, const HairStyle& style);

}  // namespace wisp::vector
