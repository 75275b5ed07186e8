// The hair base: the scalp region the roots grow from, as the camera sees it (sim/scalp.hpp),
// painted under the wisps the way illustrators lay a base coat of hair colour before the
// strands, so that no skin shows between the roots and no wisp shows a cut end there. Here it is
// traced from any scalar field over the image (positive inside): marching squares on a grid of
// `cell_px` pixels (vector/chart_contour.hpp), each crossing placed by bisection on the exact
// field, the loops fitted with cubics (vector/stroke_fit.hpp) and flattened for the arrangement
// (which decides where it shows: behind every wisp, hidden by the head and body like the hair,
// vector/arrangement.hpp). The renderer paints it as a diffusion-curve region of its own.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <utility>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "vector/hair_style.hpp"

namespace wisp::vector {

struct HairBase {
  // Closed cubic paths with the base on their left in (x, y), diffusion's left: outer boundaries
  // counter-clockwise in (x, y), holes clockwise.
  std::vector<diffusion::BezierPath> paths;
  // Each path flattened: ring vertices (the last joined to the first) and their path parameters.
  std::vector<std::vector<Eigen::Vector2d>> rings;
  std::vector<std::vector<double>> ring_s;
  // Distance from the eye to the base seen through a pixel (+infinity off it).
  std::function<double(const Eigen::Vector2d&)> depth;
  // The base's colour seen through a pixel on it (a lit coat, vector/fur.hpp); empty: one colour.
  std::function<Eigen::Vector3f(const Eigen::Vector2d&)> shade;

  bool empty() const { return paths.empty(); }
};

struct HairBaseOptions {
  double cell_px = 2;          // marching squares grid
  double fit_tolerance = 0.1;  // px: cubic paths against the exact crossings
  double flatten_tolerance = 0.05;
  double min_area = 2;  // px^2: smaller loops are dropped
};

// The region field > 0 within `box` (padded by two cells, so the region ends on the box's edges
// when it runs past them: pass a box larger than the view to keep its cut outside).
HairBase trace_hair_base(const std::function<double(const Eigen::Vector2d&)>& field,
                         std::function<double(const Eigen::Vector2d&)> depth,
                         const Eigen::AlignedBox2d& box, const HairBaseOptions& options = {});

// The base's colour in the style (BaseStyle).
Eigen::Vector3f base_color(const HairStyle& style);

// One diffusion curve per path: the base's colour on its inside (diffusion's left), or with
// `base.shade` its colour at points about 3 px apart along the path, an insulating (Neumann)
// outside, so it constrains only the base; active on `visible[i]` (the arrangement's
// WispArrangement::base_visible). Paths with no visible interval give no curve.
std::vector<diffusion::DiffusionCurve> base_curves(
    const HairBase& base, const std::vector<std::vector<std::pair<double, double>>>& visible,
    const Eigen::Vector3f& color);

}  // namespace wisp::vector
