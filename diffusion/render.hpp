// Rendering a diffusion-curve drawing end to end: rasterize at the asked size, solve colours (and
// blur values, when any curve has blur) in one multigrid solve, reblur.
#pragma once

#include <vector>

#include "diffusion/antialias.hpp"
#include "diffusion/diffusion_curve.hpp"
#include "diffusion/multigrid.hpp"
#include "diffusion/rasterize.hpp"

namespace wisp::diffusion {

struct RenderStats {
  double rasterize_ms = 0;
  double solve_ms = 0;  // multigrid setup + solve
  double antialias_ms = 0;
  double blur_ms = 0;
  bool blurred = false;
  long antialiased_pixels = 0;  // pixels re-sampled along sharp curves (antialias.hpp)
  SolveStats solver;
};

// An RGB image as three planes of width*height floats, row-major, in [0,1] up to solver error.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> planes;
};

// Curves in drawing coordinates ([0,drawing.width]x[0,drawing.height]) are scaled to a
// width x height image. Neumann sides are opaque (NeumannSides::Opaque in rasterize.hpp), as in
// small-usvg, which reads both XML dialects with that rule. With `antialias`, pixels that sharp
// curves cross mix both sides' colours by the area each covers (antialias.hpp), before the reblur.
// Throws std::invalid_argument for an invalid curve or size.
Image render_drawing(const Drawing& drawing, int width, int height,
                     const SolverOptions& solver = {}, RenderStats* stats = nullptr,
                     bool antialias = true);

}  // namespace wisp::diffusion
