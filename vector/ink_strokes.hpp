// Ink outlines: the arrangement's silhouette and occlusion polylines (exact geometry,
// vector/ink.hpp) fitted with cubic Beziers (vector/stroke_fit.hpp, Schneider's least squares: what
// Shin et al. did with Potrace from pixels, here from the exact lines) and given a width along
// them:
//  - the silhouette (hair against background or body) is thicker than the occlusion boundaries
//    inside the hair (InkStyle::silhouette_width > occlusion_width in the presets);
//  - strokes narrow towards the roots, where wisps pile up and their order changes from frame to
//    frame (Costigan and Shin both fade strokes there): the factor
//      root_width + (1 - root_width) * (1 - cos(pi * min(v / root_fade, 1))) / 2
//    of the strand parameter v at the stroke's point (Shin's root fade, over the first root_fade
//    of the strand instead of all of it), and likewise towards the tips (tip_fade, tip_width),
//    where wisps thin to a point and a full-width stroke would end in a blob;
//  - occlusion strokes taper to nothing over `end_taper` at their open ends, where the hidden
//    wisp's outline runs under the front one (a T-junction).
// Widths are given in pixels of a frame whose shorter side is InkStyle::reference_size and scaled
// by min(width, height) / reference_size, so a frame rendered at another size looks the same.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "diffusion/bezier.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_style.hpp"

namespace wisp::vector {

// The fitted path (closed for a loop) with its width along it.
struct InkCurve : diffusion::BezierPath {
  std::vector<std::pair<double, double>> width;  // (path parameter, full width px), sorted
  bool silhouette = true;                        // false: an occlusion boundary
  int wisp = -1;                                 // the wisp whose outline it follows
};

// Pixels per reference pixel for a frame of this size.
double ink_scale(const InkStyle& style, int width, int height);

// The width factor at strand parameter v: the root fade (see above) times the same fade
// mirrored at the tip (tip_fade, tip_width).
double root_factor(const InkStyle& style, double v);

// The strand parameter at the point of the wisp's outline nearest to p.
double strand_parameter_near(const Wisp& wisp, const Eigen::Vector2d& p);

std::vector<InkCurve> ink_curves(const std::vector<Wisp>& wisps, const WispArrangement& arrangement,
                                 const InkStyle& style, int width, int height);

// Width of an InkCurve at path parameter s (linear between stops, clamped at the ends).
double width_at(const std::vector<std::pair<double, double>>& stops, double s);

}  // namespace wisp::vector
