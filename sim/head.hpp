// The head the strands grow on and collide with, in its local frame (see sim/params.hpp), and its
// pose in the world. HeadGeometry is the plain description that is saved with an animation (an
// ellipsoid's radii or a triangle mesh); HeadShape adds what the simulator asks of it: a signed
// distance with its gradient (analytic for the ellipsoid, a sampled grid for a mesh) and ray hits
// from the centre, used to place roots.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "sim/params.hpp"

namespace wisp::sim {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // indices into vertices, counter-clockwise from outside
};

struct HeadGeometry {
  HeadKind shape = HeadKind::Ellipsoid;
  Eigen::Vector3d radii{0.078, 0.105, 0.095};
  TriangleMesh mesh;  // shape Mesh only, head-local metres
};

// A rigid head pose: world = rotation * local + position.
struct HeadPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();

  Eigen::Vector3d to_world(const Eigen::Vector3d& local) const {
    return rotation * local + position;
  }
  Eigen::Vector3d to_local(const Eigen::Vector3d& world) const {
    return rotation.conjugate() * (world - position);
  }
};

class HeadShape {
 public:
  // Throws std::invalid_argument for non-positive radii, an empty or open mesh.
  explicit HeadShape(HeadGeometry geometry);

  const HeadGeometry& geometry() const { return geometry_; }

  // Signed distance from the surface (negative inside, metres, head-local) and, if `normal` is
  // given, the unit outward gradient. For the ellipsoid this is the usual first-order estimate
  // |p/r| (|p/r| - 1) / |p/r^2|, exact on the surface; for a mesh, trilinear on a grid.
  double distance(const Eigen::Vector3d& p, Eigen::Vector3d* normal = nullptr) const;

  // The surface point hit by the ray from the head's centre along `direction` (head-local).
  Eigen::Vector3d surface_point(const Eigen::Vector3d& direction) const;

  // Centre and half extents of the head's bounding box (head-local).
  Eigen::Vector3d center() const { return center_; }
  Eigen::Vector3d half_extent() const { return half_extent_; }

 private:
  HeadGeometry geometry_;
  bool mesh_ = false;  // geometry_.shape == HeadKind::Mesh, cached for the hot distance queries
  Eigen::Vector3d center_, half_extent_;
  // Mesh signed-distance grid: n.x() * n.y() * n.z() samples from `origin_` with spacing `cell_`.
  Eigen::Vector3i n_ = Eigen::Vector3i::Zero();
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 0;
  std::vector<float> sdf_;

  void build_mesh_grid();
  double grid_value(const Eigen::Vector3d& p) const;
};

}  // namespace wisp::sim
