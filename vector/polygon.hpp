// Plain polygon helpers shared by the arrangement (mask rings), the style (chart polygons), the
// renderer (which pixels the hair mask holds) and the inspector (picking, face fills): a ring is a
// closed polygon given by its vertices, the last joined to the first.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "vector/buckets.hpp"

namespace wisp::vector {

// Whether p is inside the ring by the even-odd rule (a ray towards +x crosses it an odd number
// of times). Points on the boundary may go either way.
inline bool inside_polygon(const std::vector<Eigen::Vector2d>& ring, const Eigen::Vector2d& p) {
  bool in = false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Eigen::Vector2d &a = ring[i], &b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

// Signed area (shoelace): positive when the ring turns counter-clockwise in (x, y).
inline double signed_area(const std::vector<Eigen::Vector2d>& ring) {
  double a = 0;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    a += ring[j].x() * ring[i].y() - ring[i].x() * ring[j].y();
  return 0.5 * a;
}

// Sets pixels[y * width + x] = value for every pixel whose centre (x + 0.5, y + 0.5) lies inside
// `rings` (even-odd over all of them, so holes are rings too). Exact centre sampling, unlike a
// rasterizer's non-anti-aliased fill, which may move thin slivers by up to half a pixel.
template <class T>
void fill_centres(std::vector<T>& pixels, int width, int height,
                  const std::vector<std::vector<Eigen::Vector2d>>& rings, T value) {
  double y_min = height, y_max = 0;
  for (const auto& r : rings)
    for (const Eigen::Vector2d& p : r)
      y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
  const int row0 = std::max(0, int(std::floor(y_min))), row1 = std::min(height, int(y_max) + 1);
  // Each edge (its end points) in the bucket of the first row it may cross; an edge with an end
  // that is not a number from the first row on, to be tested as before at every row.
  struct Edge {
    const Eigen::Vector2d *a, *b;
    double top;  // the larger y: the edge crosses no row centre from there on
  };
  const Buckets<Edge> starting = bucket<Edge>(std::max(0, row1 - row0) + 1, [&](const auto& put) {
    for (const auto& r : rings)
      for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        const double lo = std::min(r[i].y(), r[j].y()), hi = std::max(r[i].y(), r[j].y());
        const bool finite = std::isfinite(lo) && std::isfinite(hi);
        if (finite && (hi < row0 || lo >= row1)) continue;
        const int first = finite ? std::clamp(int(std::floor(lo)) - 1, row0, row1) : row0;
        put(first - row0, Edge{&r[i], &r[j], finite ? hi : INFINITY});
      }
  });
  std::vector<Edge> active;
  std::vector<double> xs;
  for (int y = row0; y < row1; ++y) {
    const double yc = y + 0.5;
    active.insert(active.end(), starting.items.begin() + starting.begin[size_t(y - row0)],
                  starting.items.begin() + starting.begin[size_t(y - row0) + 1]);
    active.erase(
        std::remove_if(active.begin(), active.end(), [&](const Edge& e) { return e.top < yc - 1; }),
        active.end());
    xs.clear();
    for (const Edge& e : active) {
      const Eigen::Vector2d &pi = *e.a, &pj = *e.b;
      if ((pi.y() > yc) != (pj.y() > yc))
        xs.push_back(pj.x() + (yc - pj.y()) * (pi.x() - pj.x()) / (pi.y() - pj.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Pixels x with x + 0.5 in [xs[k], xs[k+1]).
      const int x0 = std::max(0, int(std::ceil(xs[k] - 0.5)));
      const int x1 = std::min(width, int(std::ceil(xs[k + 1] - 0.5)));
      for (int x = x0; x < x1; ++x) pixels[size_t(y) * width + x] = value;
    }
  }
}

}  // namespace wisp::vector
