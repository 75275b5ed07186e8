// Wisps as diffusion curves. Each wisp's closed outline becomes one DiffusionCurve whose inside
// (diffusion's left: the outline turns counter-clockwise in (x, y)) carries the wisp's colours
// and whose outside carries the shadow colour, constrained only on the outline's visible
// intervals (from the arrangement).
//
// hair_curves: Faraj's colouring (the hair colour inside with one colour point, shadow outside).
// shade_hair: every style. With lit shading the inside colours come from the light on the wisp
// as a tube (vector/wisp_shader.hpp) at the outline (u = +-1), and curves inside the wisp carry
// what diffusion from the outline alone cannot:
//  - the centre line (u = 0) with the colour there: the lit side of a tube peaks inside it;
//  - at each hard edge of the toon ramp, the level set of the ramp's x in the wisp's chart, with
//    the two bands' colours on its two sides (diffusion alone would blend them smoothly);
//  - highlights (vector/highlights.hpp): closed, the highlight colour inside, an insulating
//    (Neumann) side outside so the shading around them is undisturbed; an outline in front of
//    another wisp's highlight carries the highlight colour outside instead of the shadow colour.
// These are built in the wisp's chart, so they lie inside the wisp, and are active only where
// the wisp is visible (vector/visible_region.hpp: the arrangement's faces whose front-most wisp
// it is) and, for the centre line and band edges, outside the wisp's highlights.
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
// (ArrangementOptions::debug_view) to be clipped to where their wisp shows.
bool needs_visible_regions(const HairStyle& style);

struct HairCurveStats {
  int outlines = 0, centre_lines = 0, band_edges = 0, highlights = 0;
};

struct HairCurves {
  std::vector<diffusion::DiffusionCurve> curves;  // outlines first (wisp order), then the rest
  std::vector<int> outline_of;  // per wisp: the index of its outline in `curves`, or -1
  HairCurveStats stats;
};

// All the diffusion curves of a frame in the given style. `frame` supplies the light, the eye and
// the strands' 3D samples (by ProjectedStrand::id == Wisp::strand). Without the arrangement's
// faces (empty view) no curves are drawn inside wisps.
HairCurves shade_hair(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                      const WispArrangement& arrangement, const HairStyle& style);

}  // namespace wisp::vector
