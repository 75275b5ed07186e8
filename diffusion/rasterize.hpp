// Rasterizer: diffusion curves at a given resolution -> the discrete Problem (problem.hpp).
//
// Sampling rule. A curve lives between pixel centres. It is flattened far below a pixel, and every
// place where it crosses a link (the segment joining two 4-neighbour pixel centres) is a
// crossing, found exactly with a half-open rule so that no crossing is counted twice or missed.
//  - Every crossed link is cut: no colour diffuses through a curve, so neither side can leak
//    into the other, however thin the feature (a closed curve that crosses the grid separates
//    its inside from its outside in the link graph, by the Jordan curve theorem).
//  - Each of the link's two pixels receives a claim from the side of the curve that faces it,
//    at distance |pixel centre - crossing| along the link. A pixel takes the colour of its
//    nearest Dirichlet claim (ties: the first curve in drawing order). Neumann sides claim
//    nothing: they only cut.
//  - A crossing whose second pixel lies outside the image still claims the inside pixel.
//  - Thin features: where two curves (or the two sides of a thin wisp) cross the same link,
//    each pixel takes the claim nearest to it, so it always gets the colour of the side that
//    faces it; a feature thinner than the pixel spacing between two centres simply has no
//    pixel inside it.
//  - Gradient curves cut nothing and fix nothing: each crossing adds the colour jump across the
//    curve to the link's gradient field, and the problem's right-hand side becomes div w.
//  - Only the curve's active parameter intervals take part.
#pragma once

#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "diffusion/problem.hpp"

namespace wisp::diffusion {

struct RasterizeOptions {
  double flatten_tolerance = 0.01;  // pixels: how far the flattened polyline may stray
  bool blur_channel = false;        // add each claim's blur sigma as a 4th channel
};

// Curves must be valid (see validate()) and in pixel coordinates of a width x height image.
Problem rasterize(const std::vector<DiffusionCurve>& curves, int width, int height,
                  const RasterizeOptions& options = {});

}  // namespace wisp::diffusion
