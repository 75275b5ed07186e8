// Body occluders: silhouettes and per-pixel depth of the body's closed surfaces (see
// body_occluders.hpp).
#include "apps/render/body_occluders.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "sim/surface_rays.hpp"

namespace wisp::render {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

double cross(const Vector2d& o, const Vector2d& a, const Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Leaves out the points well inside the polygon of the extreme points in eight directions (Akl
// and Toussaint): none is a corner of the hull, and a surface's thousands of vertices come down
// to the few near its outline before the hull's sort.
void drop_inner(std::vector<Vector2d>& p) {
  if (p.size() < 16) return;
  // Extreme in x, x + y, y, y - x, -x, ..., counter-clockwise (the order of their directions).
  const double dx[8] = {1, 1, 0, -1, -1, -1, 0, 1}, dy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  Vector2d extreme[8];
  double best[8];
  for (int k = 0; k < 8; ++k) best[k] = -INFINITY;
  Eigen::AlignedBox2d box;
  for (const Vector2d& q : p) {
    box.extend(q);
    for (int k = 0; k < 8; ++k)
      if (const double v = dx[k] * q.x() + dy[k] * q.y(); v > best[k]) best[k] = v, extreme[k] = q;
  }
  std::vector<Vector2d> ring;
  for (const Vector2d& q : extreme)
    if (ring.empty() || (q != ring.back() && q != ring.front())) ring.push_back(q);
  if (ring.size() < 3) return;
  // Inside every edge by far more than the rounding of the cross products.
  const double margin = 1e-9 * box.sizes().squaredNorm();
  p.erase(std::remove_if(p.begin(), p.end(),
                         [&](const Vector2d& q) {
                           for (size_t k = 0; k < ring.size(); ++k)
                             if (!(cross(ring[k], ring[(k + 1) % ring.size()], q) > margin))
                               return false;
                           return true;
                         }),
          p.end());
}

// Convex hull (Andrew's monotone chain), counter-clockwise in (x, y).
std::vector<Vector2d> convex_hull(std::vector<Vector2d> p) {
  drop_inner(p);
  std::sort(p.begin(), p.end(), [](const Vector2d& a, const Vector2d& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
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

}  // namespace

std::vector<vector::Occluder> body_occluders(const sim::BodyModel& body, const sim::HeadPose& pose,
                                             const sim::Camera& camera, double bias,
                                             std::shared_ptr<const sim::SurfaceRays> head) {
  std::vector<vector::Occluder> out;
  for (sim::BodySurface& surface : body.surfaces(pose, camera.eye)) {
    bool behind = false;
    for (const Vector3d& v : surface.vertices)
      behind |= (v - camera.eye).dot(camera.forward) <= 1e-3;
    // A surface reaching behind the eye has no meaningful silhouette; it is left out.
    if (behind || surface.triangles.empty()) continue;
    // The hull's points: each vertex that is a corner, once, in the order of the triangles.
    std::vector<char> taken(surface.vertices.size(), 0);
    std::vector<int> corners;
    corners.reserve(surface.vertices.size());
    for (const Eigen::Vector3i& t : surface.triangles)
      for (int c = 0; c < 3; ++c)
        if (!taken[t[c]]) taken[t[c]] = 1, corners.push_back(t[c]);
    std::shared_ptr<const sim::SurfaceRays> s =
        surface.part == sim::kBodyHead && head
            ? head
            : std::make_shared<const sim::SurfaceRays>(std::move(surface.vertices),
                                                       std::move(surface.triangles), camera, true,
                                                       surface.neighbours);
    std::vector<Vector2d> points;
    points.reserve(corners.size());
    for (int v : corners) points.push_back(s->pixels()[size_t(v)]);
    vector::Occluder o;
    o.ring = convex_hull(points);
    if (o.ring.size() < 3) continue;
    o.depth = [s, bias](const Vector2d& p) { return s->depth(p) + bias; };
    o.max_depth = [s, bias](const Eigen::AlignedBox2d& b) { return s->max_depth(b) + bias; };
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace wisp::render
