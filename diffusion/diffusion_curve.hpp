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
  // The outline of gradient mesh `mesh_outline` of the drawing (gradient_mesh.hpp), or -1. The
  // rasterizer makes its Dirichlet side consistent with the mesh's own colours inside.
  int mesh_outline = -1;
};

// A Poisson curve (Hou et al., "Poisson Vector Graphics", TVCG 2020, as small-usvg solves it): a
// path that fixes no colour and cuts nothing, with RGB weights along it. As in small-usvg, the
// weight is a source of +w on the pixels left of the curve and -w on those right of it: a dipole
// layer, so the colour steps up by w (times the drawing's area over 1024^2, small-usvg's scale)
// from the left side to the right side, and the rest of the drawing decides the absolute colour.
// Weights may be negative; their stops share the path parameter t of the BezierPath.
struct PoissonCurve : BezierPath {
  std::vector<ColorStop> weights;
};

// A gradient mesh (Ferguson patches, as in small-usvg): a grid of rows x cols tiles over
// (rows+1) x (cols+1) vertices, row-major (a row runs along u, rows follow each other along v).
// Each vertex has a position and a colour; position tangents along u and v are optional (empty:
// estimated from the neighbours, as colour tangents always are). With `normalized`, positions and
// tangents are fractions of the drawing's size. Evaluation is in gradient_mesh.hpp.
struct GradientMesh {
  int rows = 0;
  int cols = 0;
  bool normalized = false;
  std::vector<Eigen::Vector2d> positions;
  std::vector<Color> colors;
  std::vector<Eigen::Vector2d> tangents_u, tangents_v;  // both empty or both of positions' size
};

// A whole drawing: the image size it was authored for and its primitives.
struct Drawing {
  int width = 0;
  int height = 0;
  std::vector<DiffusionCurve> curves;
  std::vector<PoissonCurve> poisson_curves;
  std::vector<GradientMesh> meshes;
};

// Colour of a side at parameter t (linear between stops, clamped outside). Empty stops give black.
Color color_at(const std::vector<ColorStop>& stops, double t);
// Blur sigma at parameter t (linear between stops, clamped outside). Empty stops give 0.
float blur_at(const std::vector<BlurStop>& stops, double t);

// Throws std::invalid_argument naming the curve when it is malformed: fewer than 4 or not 3k+1
// control points, non-finite coordinates or colours, stop parameters outside [0,1] or unsorted,
// negative blur. `what` prefixes the message (for example "drawing.xml: curve 3").
void validate(const DiffusionCurve& curve, const std::string& what);
// Likewise for a Poisson curve (its weights may have any sign) and a gradient mesh (at least one
// tile, vertex counts that match, finite values, tangents both given or both absent).
void validate(const PoissonCurve& curve, const std::string& what);
void validate(const GradientMesh& mesh, const std::string& what);

}  // namespace wisp::diffusion
