// A diffusion curve (Orzan et al., "Diffusion Curves: A Vector Representation for Smooth-Shaded
// Images", SIGGRAPH 2008): a cubic Bezier path with a colour on each side, diffused into the image
// by the solver. Following Bezerra et al. ("Diffusion Constraints for Vector Graphics", NPAR 2010)
// and small-usvg, each side is either a Dirichlet boundary (it imposes its colour) or a Neumann
// one (an insulating barrier without colour).
//
// Coordinates are pixels: x to the right, y down, the image covers [0,W]x[0,H] and pixel (i,j) has
// its centre at (i+0.5, j+0.5). For a direction of travel d, the left side lies towards
// (-d.y, d.x): the mathematical left in y-up coordinates, which on screen (y down) appears on the
// right of the direction of travel. This is small-usvg's SceneXML convention; the original
// CurveSetXML files, whose x and y are swapped, come out the same way after their reader swaps
// the two colour sets.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "diffusion/bezier.hpp"

namespace wisp::diffusion {

using Color = Eigen::Vector3f;  // RGB in [0,1], interpolated and diffused as given (no gamma).

// A colour at parameter t in [0,1] along the whole path. Stops are sorted by t; between stops the
// colour is linear in t, outside them it is clamped to the first or last stop.
struct ColorStop {
  double t = 0;
  Color color = Color::Zero();
};

// A blur radius (Gaussian sigma, pixels) at parameter t; 0 keeps the curve sharp.
struct BlurStop {
  double t = 0;
  float sigma = 0;
};

enum class Boundary { Dirichlet, Neumann };

// The path (3k+1 control points, see BezierPath) with its parameter t as the one of the stops and
// the active intervals.
struct DiffusionCurve : BezierPath {
  std::vector<ColorStop> left, right;
  Boundary left_boundary = Boundary::Dirichlet;
  Boundary right_boundary = Boundary::Dirichlet;
  std::vector<BlurStop> blur;
  // A gradient curve (the Poisson variant of Orzan et al.) fixes no colour: it only prescribes the
  // jump right - left across itself, as the gradient field w of  Laplacian(u) = div w. Its
  // absolute colours come from the rest of the drawing. Boundary kinds are ignored for it.
  bool gradient_only = false;
  // Parameter intervals [t0,t1] where the curve constrains the solve; empty means everywhere.
  // Hidden parts of wisp outlines are left out this way without cutting the curve.
  std::vector<std::pair<double, double>> active;
};

// A whole drawing: the image size it was authored for and its curves.
struct Drawing {
  int width = 0;
  int height = 0;
  std::vector<DiffusionCurve> curves;
};

// Colour of a side at parameter t (linear between stops, clamped outside). Empty stops give black.
Color color_at(const std::vector<ColorStop>& stops, double t);
// Blur sigma at parameter t (linear between stops, clamped outside). Empty stops give 0.
float blur_at(const std::vector<BlurStop>& stops, double t);

// Throws std::invalid_argument naming the curve when it is malformed: fewer than 4 or not 3k+1
// control points, non-finite coordinates or colours, stop parameters outside [0,1] or unsorted,
// negative blur. `what` prefixes the message (for example "drawing.xml: curve 3").
void validate(const DiffusionCurve& curve, const std::string& what);

}  // namespace wisp::diffusion
