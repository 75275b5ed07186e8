// Curves inside a wisp, for what diffusion from its outline alone cannot draw (shade_hair in
// vector/hair_curves.hpp adds them after the outlines):
//  - the centre line (u = 0) with the colour there: the lit side of a tube peaks inside it;
//  - at each hard edge of the toon ramp, the level set of the ramp's x in the wisp's chart, with
//    the two bands' colours on its two sides (diffusion alone would blend them smoothly);
//  - highlights (vector/highlights.hpp): closed, the highlight colour inside, an insulating
//    (Neumann) side outside so the shading around them is undisturbed.
// These are built in the wisp's chart, so they lie inside the wisp, and are active only where
// the wisp is visible (vector/visible_region.hpp: the arrangement's faces whose front-most wisp
// it is) and, for the centre line and band edges, outside the wisp's highlights.
#pragma once

#include <memory>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "vector/hair_style.hpp"
#include "vector/highlights.hpp"
#include "vector/visible_region.hpp"
#include "vector/wisp_chart.hpp"
#include "vector/wisp_shader.hpp"

namespace wisp::vector {

// The highlight shapes of each wisp in its chart, in the style's HighlightShape (none for None).
// charts[w] null: wisp w is hidden and has none; samples[w]: chart t of its shading samples.
// The anime band is laid on the head (its centre and radius in `light`, its axis and the eye in
// `frame`) and cut out of every wisp that crosses it.
std::vector<std::vector<ChartPolygon>> highlight_shapes(
    const std::vector<std::unique_ptr<WispChart>>& charts,
    const std::vector<std::vector<double>>& samples, const HairStyle& style,
    const FrameLight& light, const sim::ProjectedFrame& frame);

// One visible wisp, as its inner curves are built from it.
struct WispInterior {
  int index = -1;  // the wisp's index in the arrangement
  const WispChart* chart = nullptr;
  const std::vector<double>* samples = nullptr;  // chart t of its shading samples
  const WispShader* shader = nullptr;
  const std::vector<ChartPolygon>* highlights = nullptr;  // its highlight shapes
};

struct InnerCurves {
  std::vector<diffusion::DiffusionCurve> curves;
  int centre_lines = 0, band_edges = 0, highlights = 0;
};

// Appends to `out` the curves inside one wisp that are active somewhere, in this order: its
// centre line (lit styles that draw it), its band edges (lit styles with hard bands), its
// highlights. `regions`: where each wisp of the arrangement shows.
void add_inner_curves(const WispInterior& wisp, const VisibleRegions& regions,
                      const HairStyle& style, InnerCurves& out);

}  // namespace wisp::vector
