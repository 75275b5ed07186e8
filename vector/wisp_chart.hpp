// Coordinates on a wisp: t along its centre curve (0 root, 1 tip, the centre spline's parameter)
// and u across it (+1 on the on-screen Left side of the outline, -1 on the Right, 0 on the
// centre), with the 3D frame of the strand at t. Shading fields live in (t, u); curves built in
// (t, u) with |u| <= 1 map inside the wisp's band by construction, because a point is placed by
// interpolating between the band's flattened sections (vector/wisp.hpp), whose outline sides
// never fold over.
//
// Plain (t, u) with t to the right and u up is oriented the other way from pixels (x right, y
// down, travel root -> tip): what lies to the left of a curve in (t, u) lies to diffusion/'s right
// of its image (the map's Jacobian has a negative determinant).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/projected.hpp"
#include "vector/hair_shading.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

class WispChart {
 public:
  // `strand`: the projected strand the wisp was built from (its 3D samples give the view vector);
  // throws std::invalid_argument when it has no world positions.
  WispChart(const Wisp& wisp, const sim::ProjectedStrand& strand, const Eigen::Vector3d& eye);

  double t_begin() const { return t0_; }
  double t_end() const { return t1_; }

  Eigen::Vector2d point(double t, double u) const;  // pixels
  Eigen::Vector3d tangent(double t) const;          // unit, root -> tip
  Eigen::Vector3d world(double t) const;            // on the strand
  double depth(double t) const;
  double strand_u(double t) const;
  TubeFrame frame(double t) const;  // at world(t), looking from the eye

  // Parameters covering [t_begin, t_end]: every section's t, refined so that consecutive centre
  // points are at most `step_px` apart and at least `per_span` samples fall in each span.
  std::vector<double> samples(double step_px, int per_span = 4) const;

 private:
  int section_before(double t) const;
  double control_index(double t) const;  // t in units of the centre spline's control points

  const Wisp& wisp_;
  const sim::ProjectedStrand& strand_;
  Eigen::Vector3d eye_;
  double t0_ = 0, t1_ = 1;
};

}  // namespace wisp::vector
