// A sweep (generalised cylinder): the solid the body's neck, torso and upper arms are made of.
// Along its local y axis, from 0 to `length`, each cross-section is an ellipse with half-width
// a(t) along local x and half-depth c(t) along local z, centred at z = z0(t), t = y / length:
//
//   F(x, y, z) = sqrt((x / a(t))^2 + ((z - z0(t)) / c(t))^2) <= 1.
//
// The profile a, c, z0 is given at a few samples of t and interpolated by monotone cubic Hermite
// splines (Fritsch-Carlson): no overshoot between samples, so a profile that only widens never
// bulges. The first and last intervals are caps: half ellipsoids on the second and the
// second-last sections (the rims, where the splines run flat so the surface is smooth), closing
// at the poles t = 0 and 1. One profile thus gives a neck's flare, a trapezius slope and a
// deltoid's dome.
//
// The signed distance is the usual first-order estimate (F - 1) / |grad F| between the rims, and
// the half ellipsoids' own estimate in the caps' reach: the sign is exact (F < 1 exactly
// inside), the value exact on the surface and good within centimetres, which is what collision
// and cutting need. Outside, never below a lower bound (the distance to the axis minus the
// widest section).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace wisp::sim {

struct Sweep {
  // Samples of the profile: t strictly increasing from 0 to 1; half-width and half-depth in
  // metres, >= 0, and 0 at both ends (the round caps); offset of the section's centre along
  // local z, metres.
  std::vector<double> t, half_width, half_depth, offset;
};

// Throws std::invalid_argument naming `field` when the profile is malformed.
void validate_sweep(const Sweep& sweep, const char* field);

// A Sweep ready for queries (interpolation slopes precomputed). The length is given per query,
// so one shape serves a neck whose length changes from frame to frame.
class SweepShape {
 public:
  explicit SweepShape(const Sweep& sweep);

  struct Section {
    double a = 0, c = 0, z = 0;     // half-width, half-depth, centre offset along local z
    double da = 0, dc = 0, dz = 0;  // their derivatives with respect to t
  };
  Section section(double t) const;

  // Signed distance estimate from local point p (negative inside) and the outward unit normal.
  double distance(const Eigen::Vector3d& p, double length, Eigen::Vector3d* normal = nullptr) const;

  // A cap's half ellipsoid: its centre (on the rim's section) and radii, local coordinates.
  struct Cap {
    Eigen::Vector3d center, radii;
  };
  Cap cap(bool top, double length) const;

  // The surface point at parameter t in [0,1] and angle theta around the axis (theta = 0 on +x,
  // pi/2 on +z), and the outward unit normal there.
  Eigen::Vector3d point(double t, double theta, double length) const;
  Eigen::Vector3d normal(double t, double theta, double length) const;

  // Parameters of the cross-sections from t = 0 to 1 (poles included), spaced evenly by arc
  // length along the outline of the profile, at most `spacing` metres apart (at least 2 rings,
  // at most 1024), so caps get as many rings as they need.
  std::vector<double> ring_parameters(double spacing, double length) const;

  // A lower bound of the true distance from local point p: the distance to the axis minus the
  // widest section. Much cheaper than distance(); `normal` points away from the nearest axis
  // point.
  double lower_bound(const Eigen::Vector3d& p, double length,
                     Eigen::Vector3d* normal = nullptr) const;

  // A radius around the axis that holds every section (for bounds).
  double max_radius() const { return max_radius_; }

 private:
  struct Spline {
    std::vector<double> v, m;  // values and slopes at the samples
  };
  std::vector<double> t_;
  Spline a_, c_, o_;
  double max_radius_ = 0;

  static Spline monotone(const std::vector<double>& t, const std::vector<double>& v);
  void eval(const Spline& s, double t, double& value, double& slope) const;
};

// The surface of a sweep as a triangle mesh in local coordinates: `slices` vertices per ring,
// rings at ring_parameters(spacing, length), one vertex per pole. Outward counter-clockwise
// triangles.
// `t` and `theta` receive each vertex's parameters (the neck is rebuilt from them every frame).
struct SweepMesh {
  std::vector<double> t, theta;
  std::vector<Eigen::Vector3i> triangles;
};
SweepMesh sweep_mesh(const SweepShape& shape, double length, int slices, double spacing);

// The triangles of a closed surface of vertices laid out pole first, then rings - 1 rings of
// `slices` vertices each, then the other pole (the sweep meshes' and the UV sphere's layout),
// outward counter-clockwise when (up, around) is outward.
std::vector<Eigen::Vector3i> pole_to_pole_triangles(int slices, int rings);

}  // namespace wisp::sim
