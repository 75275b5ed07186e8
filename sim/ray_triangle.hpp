// Ray-triangle intersection (Moller and Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection", JGT 1997), shared by the head's mesh (inside test, scalp points) and the body
// occluders' per-pixel depth.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace wisp::sim {

// The ray parameter h of the point o + h d where the ray meets triangle abc (from either side),
// or -1 when it misses it or runs parallel to its plane. Hits behind o give h < 0 too: callers
// that want only hits ahead test h > 0.
inline double ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                           const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-14) return -1;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return -1;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return -1;
  return e2.dot(q) / det;
}

}  // namespace wisp::sim
