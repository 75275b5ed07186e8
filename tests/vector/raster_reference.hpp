// The independent raster reference for the arrangement tests, and rasterization of the
// arrangement's own output for comparison. Per pixel centre: which wisps' outline polygons cover
// it (non-zero winding), each wisp's depth there (the cross-section through the pixel, found
// among the band cells and interpolated between the two section lines), and the front-most one.
// Nothing here shares code with vector/'s arrangement or band depth.
#pragma once

#include <vector>

#include "vector/arrangement.hpp"
#include "vector/wisp.hpp"

namespace wisp::test {

struct Raster {
  int width = 0, height = 0;
  std::vector<int> label;  // per pixel, row-major; -1 = none
  int& at(int x, int y) { return label[size_t(y) * width + x]; }
  int at(int x, int y) const { return label[size_t(y) * width + x]; }
};

// Per pixel: the front-most wisp (index into `wisps`) among those covering it, or -1.
Raster reference_front(const std::vector<vector::Wisp>& wisps, int width, int height);

// Winding number of a closed ring around p.
int winding_number(const std::vector<Eigen::Vector2d>& ring, const Eigen::Vector2d& p);

// Depth of wisp w at p: nearest of its band cells containing p at least `margin` inside (between
// the cell's section lines by inverse distance); infinity if none. With margin 0, a point in no
// cell takes the depth of the nearest section.
double reference_depth(const vector::Wisp& w, const Eigen::Vector2d& p, double margin = 0);

// Per pixel: the front-most wisp of the arrangement face containing it (from the debug view).
Raster arrangement_front(const vector::ArrangementView& view, int width, int height);

// Per pixel: 1 inside the mask polygons (even-odd over outer boundaries and holes), else 0.
Raster mask_raster(const vector::HairMask& mask, int width, int height);

// Fills every pixel whose centre is inside the polygon set (rule: non-zero winding if `nonzero`,
// else even-odd) by calling fill(x, y).
template <class Fill>
void scan_polygons(const std::vector<std::vector<Eigen::Vector2d>>& rings, int width, int height,
                   bool nonzero, Fill&& fill);

}  // namespace wisp::test

#include <algorithm>
#include <cmath>

namespace wisp::test {

template <class Fill>
void scan_polygons(const std::vector<std::vector<Eigen::Vector2d>>& rings, int width, int height,
                   bool nonzero, Fill&& fill) {
  double y0 = INFINITY, y1 = -INFINITY;
  for (const auto& r : rings)
    for (const auto& p : r) y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
  if (!(y0 <= y1)) return;
  const int j0 = std::max(0, int(std::floor(y0 - 0.5))),
            j1 = std::min(height - 1, int(std::ceil(y1)));
  std::vector<std::pair<double, int>> xs;
  for (int j = j0; j <= j1; ++j) {
    const double y = j + 0.5;
    xs.clear();
    for (const auto& r : rings)
      for (size_t i = 0, k = r.size() - 1; i < r.size(); k = i++) {
        const auto &a = r[k], &b = r[i];
        if ((a.y() > y) != (b.y() > y))
          xs.emplace_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()),
                          b.y() > a.y() ? 1 : -1);
      }
    std::sort(xs.begin(), xs.end());
    int wind = 0;
    for (size_t k = 0; k + 1 < xs.size(); ++k) {
      wind = nonzero ? wind + xs[k].second : wind ^ 1;
      if (wind == 0) continue;
      // Pixel centres x + 0.5 in [xs[k], xs[k+1]).
      const int i0 = std::max(0, int(std::ceil(xs[k].first - 0.5)));
      const int i1 = std::min(width - 1, int(std::ceil(xs[k + 1].first - 0.5)) - 1);
      for (int i = i0; i <= i1; ++i) fill(i, j);
    }
  }
}

}  // namespace wisp::test
