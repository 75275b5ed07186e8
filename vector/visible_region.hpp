// Where each wisp shows: the union of the arrangement's faces whose front-most wisp it is. Curves
// drawn inside a wisp (toon band edges, its centre line, highlights) must constrain the solve only
// there: beyond, another wisp, the head or nothing shows, and a constraint would paint this
// wisp's colours over it. Face boundaries are exactly where other outlines cross the wisp, so
// the test is a point-in-polygon over the faces' rings (even-odd: rings shared by two faces of
// the same wisp cancel), binned by rows for speed, and a curve's active intervals end where the
// test flips, found by bisection on the curve parameter.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "diffusion/bezier.hpp"
#include "vector/arrangement_view.hpp"

namespace wisp::vector {

class VisibleRegions {
 public:
  // `view`: the arrangement's faces (ArrangementOptions::keep_faces).
  VisibleRegions(const ArrangementView& view, int wisp_count);

  bool contains(int wisp, const Eigen::Vector2d& p) const;
  // Whether the segment a-b meets the boundary of the wisp's region (a sliver of another wisp
  // can cross a segment whose two ends are inside).
  bool crosses(int wisp, const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  // Sorted disjoint parameter intervals of a path where it lies in the wisp's visible region.
  // Sampled so that consecutive samples are at most `step_px` apart; each change is located to
  // 1e-4 px.
  std::vector<std::pair<double, double>> active(int wisp, const diffusion::BezierPath& path,
                                                double step_px = 0.5) const;

 private:
  struct Edge {
    Eigen::Vector2d a, b;
  };
  struct Region {
    double y0 = 0, bin = 4;  // rows of `bin` pixels from y0
    std::vector<std::vector<Edge>> rows;
    Eigen::AlignedBox2d box;
  };
  std::vector<Region> regions_;
};

// The intersection of two sorted disjoint interval lists.
std::vector<std::pair<double, double>> intersect_intervals(
    const std::vector<std::pair<double, double>>& a,
    const std::vector<std::pair<double, double>>& b);

}  // namespace wisp::vector
