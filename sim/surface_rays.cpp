// Eye rays against projected, binned triangles (see surface_rays.hpp).
#include "sim/surface_rays.hpp"

#include <algorithm>
#include <cmath>

#include "sim/ray_triangle.hpp"

namespace wisp::sim {

using Eigen::Vector2d;
using Eigen::Vector3d;

SurfaceRays::SurfaceRays(std::vector<Eigen::Matrix3d> triangles, const Camera& camera)
    : world_(std::move(triangles)), camera_(camera) {
  box_.setEmpty();
  pixel_.reserve(world_.size());
  for (const Eigen::Matrix3d& t : world_) {
    std::array<Vector2d, 3> px;
    for (int c = 0; c < 3; ++c) {
      px[c] = camera_.project(t.col(c));
      box_.extend(px[c]);
    }
    pixel_.push_back(px);
  }
  cells_ = std::clamp(int(std::sqrt(double(world_.size()))), 1, 64);
  grid_.assign(size_t(cells_) * cells_, {});
  if (box_.isEmpty()) return;
  for (int t = 0; t < int(pixel_.size()); ++t) {
    Eigen::AlignedBox2d b;
    for (const Vector2d& q : pixel_[t]) b.extend(q);
    for (int y = cell(b.min().y(), box_.min().y(), box_.max().y());
         y <= cell(b.max().y(), box_.min().y(), box_.max().y()); ++y)
      for (int x = cell(b.min().x(), box_.min().x(), box_.max().x());
           x <= cell(b.max().x(), box_.min().x(), box_.max().x()); ++x)
        grid_[size_t(y) * cells_ + x].push_back(t);
  }
}

int SurfaceRays::cell(double v, double lo, double hi) const {
  return hi > lo ? std::clamp(int((v - lo) / (hi - lo) * cells_), 0, cells_ - 1) : 0;
}

Vector3d SurfaceRays::ray(const Vector2d& p) const {
  const Camera& c = camera_;
  return (c.forward + c.right * ((p.x() - 0.5 * c.width) / c.focal_px) -
          c.up * ((p.y() - 0.5 * c.height) / c.focal_px))
      .normalized();
}

double SurfaceRays::depth(const Vector2d& p) const {
  if (box_.isEmpty() || !box_.contains(p)) return INFINITY;
  const Vector3d dir = ray(p);
  double best = INFINITY;
  const auto& bucket = grid_[size_t(cell(p.y(), box_.min().y(), box_.max().y())) * cells_ +
                             cell(p.x(), box_.min().x(), box_.max().x())];
  for (int t : bucket) {
    const double d =
        ray_triangle(camera_.eye, dir, world_[t].col(0), world_[t].col(1), world_[t].col(2));
    if (d > 0) best = std::min(best, d);
  }
  return best;
}

}  // namespace wisp::sim
