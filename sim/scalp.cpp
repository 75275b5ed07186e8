// The scalp's coverage field and its view from a camera (see scalp.hpp).
#include "sim/scalp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wisp::sim {

using Eigen::Vector3d;
using Eigen::Vector3i;

Scalp::Scalp(std::vector<Vector3d> roots, double spread) : roots_(std::move(roots)) {
  if (roots_.empty()) throw std::invalid_argument("scalp: no roots");
  if (!(spread > 0) || !std::isfinite(spread))
    throw std::invalid_argument("scalp: spread must be a positive number");
  Eigen::AlignedBox3d box;
  for (const Vector3d& r : roots_) {
    if (!r.allFinite()) throw std::invalid_argument("scalp: a root is not finite");
    box.extend(r);
  }
  // Mean nearest-neighbour distance (quadratic, once per animation: a few hundred roots).
  double spacing = 0;
  int counted = 0;
  for (size_t i = 0; i < roots_.size(); ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < roots_.size(); ++j)
      if (j != i) nearest = std::min(nearest, (roots_[i] - roots_[j]).squaredNorm());
    if (std::isfinite(nearest) && nearest > 0) spacing += std::sqrt(nearest), ++counted;
  }
  // A single root (or all at one point): a patch of about 1 cm.
  spacing = counted > 0 ? spacing / counted : 0.01;
  sigma_ = spread * spacing;

  cell_ = 3 * sigma_;
  origin_ = box.min() - Vector3d::Constant(cell_);
  cells_ = ((box.max() - box.min()) / cell_).array().floor().cast<int>() + 3;
  grid_.assign(size_t(cells_.prod()), {});
  for (int i = 0; i < int(roots_.size()); ++i) {
    const Vector3i c = cell_of(roots_[i]);
    grid_[(size_t(c.z()) * cells_.y() + c.y()) * cells_.x() + c.x()].push_back(i);
  }
  std::vector<double> at_roots;
  for (const Vector3d& r : roots_) at_roots.push_back(sum(r));
  std::nth_element(at_roots.begin(), at_roots.begin() + at_roots.size() / 2, at_roots.end());
  reference_ = at_roots[at_roots.size() / 2];
}

Vector3i Scalp::cell_of(const Vector3d& p) const {
  const Vector3d g = (p - origin_) / cell_;
  return Vector3i(std::clamp(int(std::floor(g.x())), 0, cells_.x() - 1),
                  std::clamp(int(std::floor(g.y())), 0, cells_.y() - 1),
                  std::clamp(int(std::floor(g.z())), 0, cells_.z() - 1));
}

double Scalp::sum(const Vector3d& p) const {
  // Beyond the grid every root is more than 3 sigma away: nothing worth adding.
  const Vector3d g = (p - origin_) / cell_;
  if ((g.array() < -1).any() || (g.array() > cells_.cast<double>().array() + 1).any()) return 0;
  const Vector3i c = cell_of(p);
  const double k = -0.5 / (sigma_ * sigma_);
  double s = 0;
  for (int z = std::max(0, c.z() - 1); z <= std::min(cells_.z() - 1, c.z() + 1); ++z)
    for (int y = std::max(0, c.y() - 1); y <= std::min(cells_.y() - 1, c.y() + 1); ++y)
      for (int x = std::max(0, c.x() - 1); x <= std::min(cells_.x() - 1, c.x() + 1); ++x)
        for (int i : grid_[(size_t(z) * cells_.y() + y) * cells_.x() + x])
          s += std::exp(k * (p - roots_[i]).squaredNorm());
  return s;
}

double Scalp::coverage(const Vector3d& local) const {
  return sum(local) / reference_;
}

std::vector<Vector3d> local_roots(const StrandFrame& frame) {
  std::vector<Vector3d> out;
  out.reserve(frame.strands.size());
  for (const Polyline& s : frame.strands)
    if (!s.empty()) out.push_back(frame.head.to_local(s.front()));
  return out;
}

ScalpView::ScalpView(std::shared_ptr<const Scalp> scalp, const HeadPose& pose,
                     std::shared_ptr<const SurfaceRays> head, double level)
    : scalp_(std::move(scalp)), pose_(pose), rays_(std::move(head)), level_(level) {
  if (!scalp_ || !rays_) throw std::invalid_argument("ScalpView: no scalp or no head");
}

double ScalpView::field(const Eigen::Vector2d& p) const {
  const double d = rays_->depth(p);
  if (!std::isfinite(d)) return -level_;
  const Vector3d world = rays_->camera().eye + d * rays_->ray(p);
  return scalp_->coverage(pose_.to_local(world)) - level_;
}

}  // namespace wisp::sim
