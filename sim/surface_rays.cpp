// Eye rays against projected, binned triangles (see surface_rays.hpp).
#include "sim/surface_rays.hpp"

#include <algorithm>
#include <cmath>

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
    const Vector3d a = world_[t].col(0), e1 = world_[t].col(1) - a, e2 = world_[t].col(2) - a;
    const Vector3d q = dir.cross(e2);
    const double det = e1.dot(q);
    if (std::abs(det) < 1e-14) continue;
    const Vector3d s = camera_.eye - a;
    const double u = s.dot(q) / det;
    if (u < 0 || u > 1) continue;
    const Vector3d r = s.cross(e1);
    const double v = dir.dot(r) / det;
    if (v < 0 || u + v > 1) continue;
    const double d = e2.dot(r) / det;
    if (d > 0) best = std::min(best, d);
  }
  return best;
}

}  // namespace wisp::sim
