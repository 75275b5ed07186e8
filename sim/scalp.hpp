// The scalp: the part of the head's surface that the hair grows from, as the region its roots
// span. A smooth coverage field over head-local points,
//   c(x) = sum_i exp(-|x - r_i|^2 / (2 sigma^2)) / c_ref,
// with sigma = `spread` times the mean distance from a root to its nearest neighbour and c_ref
// the median of the sum at the roots themselves: about 1 amid the roots whatever their density,
// 1/2 near the edge of the area they cover (a half-plane of evenly spread roots gives half the
// interior value on its edge line, about half a spacing beyond the outermost roots) and 0 far
// from them. Its level set c = `level` on the head is the hairline: a smooth curve around all
// the roots that bridges the gaps between neighbours (blue-noise roots leave no dips near 1/2
// inside) and follows the hair's outline in the large: parting, temples, nape.
//
// ScalpView is the scalp seen by a camera in one frame: through a pixel, the eye ray's first
// point on the head (the posed head's triangles, sim/surface_rays.hpp), and the coverage there
// minus the level: positive where the scalp shows, negative on bare skin and off the head. Its
// zero set outlines the visible scalp, hidden by the head itself like everything else.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "sim/animation.hpp"
#include "sim/surface_rays.hpp"

namespace wisp::sim {

class Scalp {
 public:
  // `roots`: head-local root positions (on the head's surface). Throws std::invalid_argument
  // for no roots, a non-finite root or a spread that is not positive.
  explicit Scalp(std::vector<Eigen::Vector3d> roots, double spread = 1.0);

  // c(x) at a head-local point.
  double coverage(const Eigen::Vector3d& local) const;
  double sigma() const { return sigma_; }
  const std::vector<Eigen::Vector3d>& roots() const { return roots_; }

 private:
  double sum(const Eigen::Vector3d& local) const;
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;

  std::vector<Eigen::Vector3d> roots_;
  double sigma_ = 0, reference_ = 1, cell_ = 1;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3i cells_ = Eigen::Vector3i::Ones();
  std::vector<std::vector<int>> grid_;  // roots per cell
};

// The head-local roots of an animation frame's strands (roots are pinned to the head, so any
// frame gives the same).
std::vector<Eigen::Vector3d> local_roots(const StrandFrame& frame);

class ScalpView {
 public:
  // `head`: eye rays against the posed head (BodyModel::head_surface), which the body's
  // occluders may share.
  ScalpView(std::shared_ptr<const Scalp> scalp, const HeadPose& pose,
            std::shared_ptr<const SurfaceRays> head, double level = 0.5);

  // coverage - level at the head point seen through pixel p; -level off the head.
  double field(const Eigen::Vector2d& p) const;
  // Distance from the eye to that head point; +infinity off the head.
  double depth(const Eigen::Vector2d& p) const { return rays_->depth(p); }
  // The head's projected bounding box (pixels).
  const Eigen::AlignedBox2d& box() const { return rays_->box(); }

 private:
  std::shared_ptr<const Scalp> scalp_;
  HeadPose pose_;
  std::shared_ptr<const SurfaceRays> rays_;
  double level_;
};

}  // namespace wisp::sim
