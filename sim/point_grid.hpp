// A uniform grid of cubic cells over a box, binning 3D points for exact nearest-neighbour style
// searches: search() visits the cells ring by ring (Chebyshev rings around the query's cell) and
// stops once a ring lies farther than the caller's current reach. Every point in ring r is at
// least (r - 1) cells from the query, so stopping there never skips a point within reach: results
// equal a brute-force scan, in O(1) rings when the cell is about the spacing of the points.
// Used for the blue-noise roots of procedural hair and for clustering dense grooms.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace wisp::sim {

class PointGrid {
 public:
  // Cells of side about `cell` (enlarged so that no axis has more than kMaxCells) covering `box`.
  // Points inserted must lie in the box.
  PointGrid(const Eigen::AlignedBox3d& box, double cell) : origin_(box.min()) {
    const Eigen::Vector3d extent = box.sizes().cwiseMax(0.0);
    cell_ = std::max({cell, extent.maxCoeff() / kMaxCells, 1e-9});
    for (int k = 0; k < 3; ++k) dims_[k] = std::max(1, int(std::ceil(extent[k] / cell_)) + 1);
    first_.assign(std::size_t(dims_[0]) * dims_[1] * dims_[2], -1);
  }

  double cell() const { return cell_; }

  void insert(const Eigen::Vector3d& p, int index) {
    const int c = cell_index(coords(p));
    points_.push_back({p, index, first_[c]});
    first_[c] = int(points_.size()) - 1;
  }

  // Calls visit(index, point) for the points of ring 0, 1, 2... around p's cell. Before ring
  // r >= 2 it reads reach() (a squared distance) and stops when ((r - 1) cell)^2 >= reach: no
  // point left can be nearer than that.
  template <class Visit, class Reach>
  void search(const Eigen::Vector3d& p, Visit&& visit, Reach&& reach) const {
    const Eigen::Vector3i c = coords(p);
    const int rings = std::max({dims_[0], dims_[1], dims_[2]});
    for (int r = 0; r < rings; ++r) {
      if (r >= 2) {
        const double gap = (r - 1) * cell_;
        if (gap * gap >= reach()) return;
      }
      for (int dz = -r; dz <= r; ++dz)
        for (int dy = -r; dy <= r; ++dy) {
          const bool face = std::abs(dz) == r || std::abs(dy) == r;
          for (int dx = -r; dx <= r; dx += face ? 1 : std::max(1, 2 * r)) {
            const Eigen::Vector3i q = c + Eigen::Vector3i(dx, dy, dz);
            if ((q.array() < 0).any() || q.x() >= dims_[0] || q.y() >= dims_[1] ||
                q.z() >= dims_[2])
              continue;
            for (int k = first_[cell_index(q)]; k >= 0; k = points_[k].next)
              visit(points_[k].index, points_[k].p);
          }
        }
    }
  }

 private:
  static constexpr int kMaxCells = 256;
  struct Entry {
    Eigen::Vector3d p;
    int index, next;
  };
  Eigen::Vector3d origin_;
  double cell_ = 1;
  int dims_[3] = {1, 1, 1};
  std::vector<int> first_;  // per cell: its last inserted entry, -1 when empty
  std::vector<Entry> points_;

  Eigen::Vector3i coords(const Eigen::Vector3d& p) const {
    Eigen::Vector3i c;
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(int(std::floor((p[k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
    return c;
  }
  int cell_index(const Eigen::Vector3i& c) const {
    return (c.z() * dims_[1] + c.y()) * dims_[0] + c.x();
  }
};

}  // namespace wisp::sim
