// Body occluders: silhouettes and per-pixel depth of the body's closed surfaces (see
// body_occluders.hpp).
#include "apps/render/body_occluders.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "sim/ray_triangle.hpp"

namespace wisp::render {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// Convex hull (Andrew's monotone chain), counter-clockwise in (x, y).
std::vector<Vector2d> convex_hull(std::vector<Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Vector2d& a, const Vector2d& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  const auto cross = [](const Vector2d& o, const Vector2d& a, const Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Vector2d> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// One surface: its triangles in world space and a coarse grid over their projections, so that
// a depth query only tests the triangles near the pixel.
struct Surface {
  std::vector<Eigen::Matrix3d> world;
  std::vector<std::array<Vector2d, 3>> pixel;
  Eigen::AlignedBox2d box;
  int cells = 1;
  std::vector<std::vector<int>> grid;
  sim::Camera camera;
  double bias = 0;

  int cell(double v, double lo, double hi) const {
    return std::clamp(int((v - lo) / (hi - lo) * cells), 0, cells - 1);
  }

  void build() {
    cells = std::clamp(int(std::sqrt(double(world.size()))), 1, 64);
    grid.assign(size_t(cells) * cells, {});
    for (int t = 0; t < int(pixel.size()); ++t) {
      Eigen::AlignedBox2d b;
      for (const Vector2d& q : pixel[t]) b.extend(q);
      for (int y = cell(b.min().y(), box.min().y(), box.max().y());
           y <= cell(b.max().y(), box.min().y(), box.max().y()); ++y)
        for (int x = cell(b.min().x(), box.min().x(), box.max().x());
             x <= cell(b.max().x(), box.min().x(), box.max().x()); ++x)
          grid[size_t(y) * cells + x].push_back(t);
    }
  }

  // Distance along the eye ray through pixel p to the nearest triangle.
  double depth(const Vector2d& p) const {
    if (!box.contains(p)) return INFINITY;
    const Vector3d dir =
        (camera.forward + camera.right * ((p.x() - 0.5 * camera.width) / camera.focal_px) -
         camera.up * ((p.y() - 0.5 * camera.height) / camera.focal_px))
            .normalized();
    double best = INFINITY;
    const auto& bucket = grid[size_t(cell(p.y(), box.min().y(), box.max().y())) * cells +
                              cell(p.x(), box.min().x(), box.max().x())];
    for (int t : bucket) {
      const double d =
          sim::ray_triangle(camera.eye, dir, world[t].col(0), world[t].col(1), world[t].col(2));
      if (d > 0) best = std::min(best, d);
    }
    return best + bias;
  }
};

}  // namespace

std::vector<vector::Occluder> body_occluders(const sim::BodyModel& body, const sim::HeadPose& pose,
                                             const sim::Camera& camera, double bias) {
  std::vector<vector::Occluder> out;
  for (const sim::BodySurface& surface : body.surfaces(pose, camera.eye)) {
    auto s = std::make_shared<Surface>();
    s->camera = camera;
    s->bias = bias;
    std::vector<Vector2d> points;
    bool behind = false;
    for (const Vector3d& v : surface.vertices) {
      behind |= (v - camera.eye).dot(camera.forward) <= 1e-3;
      points.push_back(camera.project(v));
      s->box.extend(points.back());
    }
    for (const Eigen::Vector3i& t : surface.triangles) {
      Eigen::Matrix3d tri;
      tri << surface.vertices[t[0]], surface.vertices[t[1]], surface.vertices[t[2]];
      s->world.push_back(tri);
      s->pixel.push_back({points[t[0]], points[t[1]], points[t[2]]});
    }
    // A surface reaching behind the eye has no meaningful silhouette; it is left out.
    if (behind || points.size() < 3) continue;
    s->build();
    vector::Occluder o;
    o.ring = convex_hull(points);
    if (o.ring.size() < 3) continue;
    o.depth = [s](const Vector2d& p) { return s->depth(p); };
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace wisp::render
