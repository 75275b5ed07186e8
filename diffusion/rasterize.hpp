// Rasterizer: diffusion curves at a given resolution -> the discrete Problem (problem.hpp).
//
// Sampling rule. A curve lives between pixel centres. It is flattened far below a pixel, and every
// place where it crosses a link (the segment joining two 4-neighbour pixel centres) is a
// crossing, found exactly with a half-open rule so that no crossing is counted twice or missed.
//  - Every crossed link is cut: no colour diffuses through a curve, so neither side can leak
//    into the other, however thin the feature (a closed curve that crosses the grid separates
//    its inside from its outside in the link graph, by the Jordan curve theorem).
//  - Each of the link's two pixels receives a claim from the side of the curve that faces it,
//    at distance theta = |pixel centre - crossing| along the link, in link lengths. On each link
//    only the nearest claim counts (ties: the first curve in drawing order). Neumann sides impose
//    no colour; whether they claim at all is NeumannSides:
//     - Opaque (the default; small-usvg's rule): a Neumann side claims like a Dirichlet one,
//       and a link whose nearest claim is Neumann anchors nothing. Around a feature thinner than
//       a link whose outer sides are Neumann (crane's feathers and legs, a hair highlight
//       narrower than a pixel), the pixels outside then stay free instead of taking the inside
//       colour of the far side: with Transparent sides a 512² toon frame's highlights glowed
//       into their wisps (1:1 error p99 18.1 -> 13.8 with Opaque, curly scene).
//     - Transparent (for comparison): a Neumann side claims nothing, it only cuts, so it never
//       hides a Dirichlet colour behind it on the same link.
//  - Second order (DirichletSampling::ShortleyWeller, the default): a pixel with claims stays an
//    unknown. Each link's claim acts as a neighbour at distance theta holding the side's colour
//    c (the ghost point of Shortley and Weller, 1938), so the pixel's equation gains
//    (c - u_p) / theta per claimed link: the anchor of problem.hpp, w_p = sum 1/theta and
//    a_p = (sum c / theta) / w_p. The boundary sits where the curve is, to second order; a
//    straight edge between parallel curves gives the exact linear profile. A claim closer than
//    kMinAnchorDistance fixes the pixel to its colour instead, so that weights stay bounded.
//  - First order (DirichletSampling::NearestClaim, for comparison): a pixel is fixed to the
//    colour of its nearest claim over all its links (left free if that claim is Neumann). The
//    boundary moves by up to a pixel.
//  - A crossing whose second pixel lies outside the image still claims the inside pixel.
//  - Thin features: where two curves (or the two sides of a thin wisp) cross the same link,
//    each pixel takes the claim nearest to it, so it always gets the colour of the side that
//    faces it; a feature thinner than the pixel spacing between two centres simply has no
//    pixel inside it.
//  - Gradient curves cut, anchor and fix nothing: each crossing adds the colour jump across the
//    curve to the link's gradient field, and the problem's right-hand side becomes div w.
//  - Only the curve's active parameter intervals take part.
//  - Gradient meshes (gradient_mesh.hpp), when given: a pixel that a mesh owns and that is not
//    fixed gets as right-hand side the mesh colour's differences over its open links to pixels
//    of the same mesh, plus (c - m_p) / theta for each anchor on the mesh's own outline, where
//    m_p is the mesh colour at the pixel: exactly the operator applied to the mesh colours, so a
//    mesh alone solves to them.
#pragma once

#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "diffusion/gradient_mesh.hpp"
#include "diffusion/problem.hpp"

namespace wisp::diffusion {

enum class DirichletSampling { ShortleyWeller, NearestClaim };  // see the sampling rule above
enum class NeumannSides { Transparent, Opaque };                // likewise

// Claims nearer to a pixel centre than this (link lengths) fix the pixel: the boundary moves by
// less than it, and anchor weights stay below its inverse, so the operator stays well scaled.
constexpr float kMinAnchorDistance = 1e-3f;

struct RasterizeOptions {
  double flatten_tolerance = 0.01;  // pixels: how far the flattened polyline may stray
  bool blur_channel = false;        // add each claim's blur sigma as a 4th channel (anchored too)
  // One channel only: each claim's blur sigma (Orzan's blur map on its own). Gradient curves
  // take no part.
  bool blur_only = false;
  DirichletSampling dirichlet = DirichletSampling::ShortleyWeller;
  NeumannSides neumann = NeumannSides::Opaque;
};

// Curves must be valid (see validate()) and in pixel coordinates of a width x height image.
// `meshes`, when given, is the coverage of the drawing's gradient meshes at this size; their
// outlines must be among the curves, tagged (DiffusionCurve::mesh_outline).
Problem rasterize(const std::vector<DiffusionCurve>& curves, int width, int height,
                  const RasterizeOptions& options = {}, const MeshRaster* meshes = nullptr);

// A rectangle of pixels of a larger image: columns [x, x + width), rows [y, y + height).
struct PixelWindow {
  int x = 0, y = 0, width = 0, height = 0;

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  bool operator==(const PixelWindow& o) const {
    return x == o.x && y == o.y && width == o.width && height == o.height;
  }
};

// The problem of the pixels of `window` alone, as if the image ended at the window's edges
// (links leaving it do not exist: a Neumann border, like the image's own). Its pixel (i, j) is the
// image's pixel (window.x + i, window.y + j); inside the window the constraints are those that
// rasterizing the whole image gives there. No gradient meshes.
Problem rasterize(const std::vector<DiffusionCurve>& curves, const PixelWindow& window,
                  const RasterizeOptions& options = {});

// The window of a width x height image that holds every curve (its control points, which bound
// it) with `margin` pixels around, its corners on multiples of `align` pixels (or the image's
// edges). Empty (all zero) without curves. A solve restricted to it leaves out only pixels that
// are farther than `margin` from any curve.
PixelWindow curves_window(const std::vector<DiffusionCurve>& curves, int width, int height,
                          int margin, int align);

}  // namespace wisp::diffusion
