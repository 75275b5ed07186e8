// The wisp's centre curve through its projected samples: the centripetal Catmull-Rom spline,
// converted exactly to cubic Bezier form (Yuksel, Schaefer and Keyser, "Parameterization and
// applications of Catmull-Rom curves", CAD 2011: the centripetal variant never forms cusps or
// self-intersections inside a span, which the uniform one does when projected samples bunch up
// on foreshortened strands).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "diffusion/bezier.hpp"

namespace wisp::vector {

// The spline through `points` (at least 2, no two consecutive points equal) as a path with one
// piece (span) per pair of consecutive points: span i runs from points[i] to points[i+1]. The end
// tangents use reflected phantom points, so a 2-point input gives a straight span. The spline is
// C1 in its chordal knot parameter and G1 in the per-span parameter u. Empty for fewer than 2
// points.
diffusion::BezierPath catmull_rom_path(const std::vector<Eigen::Vector2d>& points);

}  // namespace wisp::vector
