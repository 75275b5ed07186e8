// Wisps as diffusion curves: each wisp's closed outline becomes one DiffusionCurve whose inside
// carries the hair colour (with Faraj's colour point) and whose outside carries the shadow
// colour, constrained only on the outline's visible intervals (from the arrangement). The
// inside of an outline is on its left in diffusion/'s convention: the outline turns counter-
// clockwise in (x, y) and the left normal is (-d.y, d.x).
#pragma once

#include <vector>

#include "diffusion/diffusion_curve.hpp"
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

}  // namespace wisp::vector
