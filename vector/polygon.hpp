// Plain polygon helpers shared by the arrangement (mask rings), the style (chart polygons) and the
// inspector (picking): a ring is a closed polygon given by its vertices, the last joined to the
// first.
#pragma once

#include <Eigen/Core>
#include <vector>

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

}  // namespace wisp::vector
