// Level sets of a scalar field sampled on a rectilinear (t, u) grid (a wisp's chart): marching
// squares, saddles resolved by the cell's mean, crossings placed on the grid edges by bisection on
// the exact field when it is given. Contours are oriented with the higher values on their left in
// (t, u) (t to the right, u up); they end on the grid's border or close on themselves.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace wisp::vector {

struct ChartGrid {
  std::vector<double> t, u;   // ascending
  std::vector<double> value;  // value[i * u.size() + j] at (t[i], u[j])

  double at(size_t i, size_t j) const { return value[i * u.size() + j]; }
};

struct ChartContour {
  std::vector<Eigen::Vector2d> tu;  // (t, u) points
  bool closed = false;              // a loop (the first point is not repeated)
};

// `exact` (optional): the field itself, to refine each crossing.
std::vector<ChartContour> chart_contours(const ChartGrid& grid, double level,
                                         const std::function<double(double, double)>& exact = {});

}  // namespace wisp::vector
