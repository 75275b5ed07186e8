// Cubic Bezier curves and paths, the one toolkit of every stage (diffusion curves, wisp centres
// and outlines, fitted ink and chart curves, the picture's strokes), in the manner of pbrt-v4's
// util/splines.h: free functions over four control points. It lives here, in the lowest stage
// that draws curves. The rasterizer flattens paths to a tolerance far below a pixel, so that where
// a curve crosses the pixel grid is decided by the true curve, not by a coarse polygon.
//
// Several operations exist in two arithmetic forms on purpose (split at u versus subdivide at
// 1/2): each caller keeps the form its pixels were made with.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace wisp::diffusion {

// Control points P0..P3 of B(u) = sum_i C(3,i) (1-u)^(3-i) u^i P_i, u in [0,1].
using Cubic = std::array<Eigen::Vector2d, 4>;

// B(u), in Bernstein form.
Eigen::Vector2d eval(const Cubic& c, double u);
Eigen::Vector2d derivative(const Cubic& c, double u);         // dB/du
Eigen::Vector2d second_derivative(const Cubic& c, double u);  // d2B/du2

// De Casteljau at u: the parts [0,u] and [u,1], each with its own parameter in [0,1].
std::array<Cubic, 2> split(const Cubic& c, double u);
// The halves at u = 1/2, from midpoints (adaptive flattening's step).
std::array<Cubic, 2> subdivide(const Cubic& c);
// The part [u0,u1] of c, 0 <= u0 < u1 <= 1: split at u0, then the remainder at its own parameter
// of u1 (c itself when the interval is all of [0,1]).
Cubic sub_cubic(const Cubic& c, double u0, double u1);

// The same curve run from P3 to P0.
Cubic reversed(const Cubic& c);

// A straight segment a -> b as a cubic with evenly spaced control points (u is arc length / |ab|).
Cubic line_cubic(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// The box of the control points, which contains the curve (it lies in their convex hull).
Eigen::AlignedBox2d bounds(const Cubic& c);

// Number of uniform pieces in u that keep the polyline within `tolerance` of the cubic:
// the chord error of n pieces is at most max|B''| / (8 n^2) and max|B''| <= 6 max|P_i - 2P_{i+1} +
// P_{i+2}|. Clamped to [1, max_pieces] so absurd inputs cannot explode the segment count.
int flatten_pieces(const Cubic& c, double tolerance, int max_pieces);

// A path of k cubics joined end to end: 3k+1 control points, piece i being points[3i..3i+3].
// The path parameter s in [0,1] runs uniformly over the pieces: piece i covers [i/k, (i+1)/k].
// A closed path (a loop) ends on its first point. Fewer than 4 points make an empty path.
struct BezierPath {
  std::vector<Eigen::Vector2d> points;

  int piece_count() const { return points.size() >= 4 ? int(points.size() - 1) / 3 : 0; }
  Cubic piece(int i) const {
    return {points[3 * i], points[3 * i + 1], points[3 * i + 2], points[3 * i + 3]};
  }
  bool closed() const { return piece_count() > 0 && points.front() == points.back(); }

  // Adds a cubic that starts where the path ends (the first cubic also adds its start).
  void append(const Cubic& c);
};

// The point at path parameter s (clamped to [0,1]); the first point of a path without pieces,
// the origin for no points at all.
Eigen::Vector2d eval(const BezierPath& path, double s);

// A polyline vertex with the parameter t in [0,1] of the whole path it came from.
struct PathSample {
  Eigen::Vector2d p;
  double t;
};

// Adaptive flattening: each cubic is subdivided until its control polygon lies within
// `tolerance` of its chord; consecutive vertices are appended in order, the first and last
// vertex are exactly the path's end points. Empty for a path without pieces.
std::vector<PathSample> flatten(const BezierPath& path, double tolerance);

}  // namespace wisp::diffusion
