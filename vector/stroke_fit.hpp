// Least-squares fitting of cubic Bezier paths to polylines: Schneider, "An Algorithm for
// Automatically Fitting Digitized Curves" (Graphics Gems, 1990). Each piece between two corners is
// fitted by one cubic whose end points are the piece's ends and whose end tangents are fixed; the
// two free tangent lengths solve the 2x2 normal equations of the least-squares error over the
// chord-length parameters. When the worst point misses by more than the tolerance, Newton-Raphson
// reparameterisation is tried (worth it only for near misses), then the piece is split at its
// worst point with a common tangent there, so the path stays G1 except at corners.
//
// Shin et al. traced their silhouettes with Potrace from pixels; here the input is exact geometry
// (arrangement polylines, contours in a wisp's chart), so fitting only has to compress it.
//
// Guarantee (tested): every input point lies within `tolerance` of the fitted path at its
// assigned parameter (so its distance to the path is at most the tolerance).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "diffusion/bezier.hpp"

namespace wisp::vector {

struct FitOptions {
  double tolerance = 0.2;      // px: maximum distance of an input point from the path
  double corner_deg = 50;      // turning angles above this split the polyline (a kept corner)
  int max_reparameterize = 8;  // Newton-Raphson passes before a piece is split
};

// The fitted path: closed (last point == first) for a closed input of 3 or more distinct points.
struct FittedPath : diffusion::BezierPath {
  // Per input point: its parameter s on the path, non-decreasing for an open input. A loop
  // starts at its sharpest corner (point knot_index[0], s = 0) and returns to it at s = 1.
  std::vector<double> param;
  // Per cubic end (k+1 entries): the index of the input point it interpolates.
  std::vector<int> knot_index;
};

// Fits a polyline of at least 2 points (consecutive duplicates are tolerated). `closed`: the
// polyline is a loop (its last point is not a copy of the first). Fewer than two distinct points
// give an empty path.
FittedPath fit_cubics(const std::vector<Eigen::Vector2d>& points, const FitOptions& options,
                      bool closed = false);

}  // namespace wisp::vector
