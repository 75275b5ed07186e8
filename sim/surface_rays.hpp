// Eye rays against a posed triangle surface (a part of the body model, sim/body.hpp): where the
// ray through a pixel first meets the triangles. The vertices are projected once and the
// triangles binned in a coarse grid over their pixel bounding box, so a query tests only those
// near its pixel (sim/ray_triangle.hpp on each). Used for the depth of the head and body as
// occluders of the hair and for the point of the scalp seen through a pixel (sim/scalp.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "sim/camera.hpp"

namespace wisp::sim {

// Per triangle, per edge (corner e to e + 1): the edge of the triangle across it as 3 * triangle +
// edge, or -1 where no single triangle is (the mesh's border, an edge of three or more). By
// position, not by index: a seam's vertices are repeated. It depends on the mesh alone, so posed
// copies of one mesh can share the one found for it.
using EdgeNeighbours = std::vector<std::array<int, 3>>;
EdgeNeighbours edge_neighbours(const std::vector<Eigen::Vector3d>& vertices,
                               const std::vector<Eigen::Vector3i>& triangles);

class SurfaceRays {
 public:
  // `vertices`: world space; `triangles`: their indices (each vertex is a corner of about six
  // triangles: it is projected once). `with_folds`: max_depth is wanted, which needs the edges
  // where the surface's picture folds (it is +infinity without them); they are found at its
  // first call, so a surface whose bound nobody asks for does not pay for them. `neighbours`:
  // the mesh's edge_neighbours if known (found with the folds otherwise).
  SurfaceRays(std::vector<Eigen::Vector3d> vertices, std::vector<Eigen::Vector3i> triangles,
              const Camera& camera, bool with_folds = false,
              std::shared_ptr<const EdgeNeighbours> neighbours = nullptr);
  SurfaceRays(const SurfaceRays&) = delete;
  SurfaceRays& operator=(const SurfaceRays&) = delete;

  // Distance from the eye along the ray through pixel p to the nearest triangle; +infinity on a
  // miss.
  double depth(const Eigen::Vector2d& p) const;
  // An upper bound of depth() over the box, +infinity when none is found (or without folds): for
  // a box that no fold of the surface's picture meets and whose centre ray hits, the farthest any
  // triangle meeting it can be there. Lets the arrangement prove hair behind the body hidden
  // (vector/hidden_wisps.hpp).
  double max_depth(const Eigen::AlignedBox2d& box) const;
  // The unit direction of the eye ray through pixel p (the inverse of Camera::project).
  Eigen::Vector3d ray(const Eigen::Vector2d& p) const;

  const Camera& camera() const { return camera_; }
  // The triangles' projected bounding box (pixels); empty without triangles.
  const Eigen::AlignedBox2d& box() const { return box_; }
  // The projected vertices, in the order given.
  const std::vector<Eigen::Vector2d>& pixels() const { return pixel_; }

 private:
  int cell_x(double x) const;
  int cell_y(double y) const;
  std::pair<int, double> first_hit(const Eigen::Vector2d& p) const;  // triangle, distance
  void find_folds() const;
  const Eigen::Vector3d& corner(int t, int c) const { return vertex_[size_t(triangle_[t][c])]; }
  const Eigen::Vector2d& corner_pixel(int t, int c) const {
    return pixel_[size_t(triangle_[t][c])];
  }

  std::vector<Eigen::Vector3d> vertex_;
  std::vector<Eigen::Vector3i> triangle_;
  std::vector<Eigen::Vector2d> pixel_;  // per vertex
  Camera camera_;
  Eigen::AlignedBox2d box_;
  int cells_ = 1;
  // Cells per pixel along x and y. A cell is found by a multiplication, which is as monotone in
  // the coordinate as a division: a point in a triangle's box lies in a cell it was binned in.
  double scale_x_ = 0, scale_y_ = 0;
  // The triangles meeting each cell of the grid, in order: cell c's are binned_[first_[c]] to
  // binned_[first_[c + 1]] (one array, not a vector per cell).
  std::vector<int> first_, binned_;
  // Per triangle, its projected edges as lines n.p + c with n a unit normal pointing inwards
  // (nx, ny, c per edge): a ray through p can hit the triangle only where every line is at least
  // -margin, a margin far above rounding. Nine zeros (every ray is tested in 3D) for a triangle
  // seen nearly edge-on, where the 3D test's rounding is not bounded by the margin, or reaching
  // behind the eye, where the projection does not hold. A ray's cell holds about twenty
  // triangles but one or two that the ray meets (profile: 78 000 rays a 512^2 frame of the
  // default scene); the 3D test is several times this one's cost. Tested alone, without the
  // triangles' boxes: with them a cell's entries were five times the size, and building them
  // cost what the rays gained.
  std::vector<std::array<double, 9>> edge_;
  bool with_folds_ = false;
  // Filled once, by the first max_depth (which may be called from several threads).
  mutable std::once_flag folds_found_;
  mutable std::vector<std::array<bool, 3>> fold_;  // per triangle edge (corner e to e + 1): a fold
  mutable std::vector<char> fold_cell_;            // per cell: a triangle with a fold meets it
  mutable std::shared_ptr<const EdgeNeighbours> neighbour_;
};

}  // namespace wisp::sim
