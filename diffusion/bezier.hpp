// Cubic Bezier paths: evaluation and adaptive flattening into polylines that remember the path
// parameter of every vertex. The rasterizer flattens to a tolerance far below a pixel, so that
// where a curve crosses the pixel grid is decided by the true curve, not by a coarse polygon.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace wisp::diffusion {

// Point of the cubic with control points p[0..3] at local parameter s in [0,1].
Eigen::Vector2d eval_cubic(const Eigen::Vector2d* p, double s);

// A polyline vertex with the parameter t in [0,1] of the whole path it came from.
struct PathSample {
  Eigen::Vector2d p;
  double t;
};

// Flattens a path of 3k+1 control points. Each cubic is split (de Casteljau, at s = 1/2) until its
// control polygon lies within `tolerance` of its chord; consecutive vertices are appended in
// order, the first and last vertex are exactly the path's end points.
std::vector<PathSample> flatten_path(const std::vector<Eigen::Vector2d>& points, double tolerance);

}  // namespace wisp::diffusion
