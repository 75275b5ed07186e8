// Cubic Bezier pieces in the image plane: evaluation, derivatives, the flatness bound that drives
// adaptive flattening, and the exact conversion of centripetal Catmull-Rom spans to Bezier form
// (Yuksel, Schaefer and Keyser, "Parameterization and applications of Catmull-Rom curves", CAD
// 2011: the centripetal variant never forms cusps or self-intersections inside a span, which the
// uniform one does when projected samples bunch up on foreshortened strands).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace wisp::vector {

using Cubic = std::array<Eigen::Vector2d, 4>;

Eigen::Vector2d eval(const Cubic& c, double u);
Eigen::Vector2d derivative(const Cubic& c, double u);         // dB/du
Eigen::Vector2d second_derivative(const Cubic& c, double u);  // d2B/du2

// A straight segment a -> b as a cubic with evenly spaced control points (u is arc length / |ab|).
Cubic line_cubic(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Number of uniform pieces in u that keep the polyline within `tolerance` of the cubic:
// the chord error of n pieces is at most max|B''| / (8 n^2) and max|B''| <= 6 max|P_i - 2P_{i+1} +
// P_{i+2}|. Clamped to [1, max_pieces] so absurd inputs cannot explode the segment count.
int flatten_pieces(const Cubic& c, double tolerance, int max_pieces);

// Cubic Bezier spans of the centripetal Catmull-Rom spline through `points` (at least 2, no two
// consecutive points equal). Span i runs from points[i] to points[i+1]; the end tangents use
// reflected phantom points, so a 2-point input gives a straight span. The spline is C1 in its
// chordal knot parameter and G1 in the per-span parameter u.
std::vector<Cubic> catmull_rom_spans(const std::vector<Eigen::Vector2d>& points);

}  // namespace wisp::vector
