// Body occluders: silhouettes and per-pixel depth of the body's closed surfaces (see
// body_occluders.hpp).
#include "apps/render/body_occluders.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>

#include "sim/surface_rays.hpp"

namespace wisp::render {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// Triangles grouped into closed surfaces: triangles sharing a vertex (exactly the same point,
// as the model emits them) belong together.
std::vector<std::vector<int>> surfaces(const std::vector<Eigen::Matrix3d>& tris) {
  std::vector<int> parent(tris.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::array<double, 3>, int> owner;
  for (int t = 0; t < int(tris.size()); ++t)
    for (int c = 0; c < 3; ++c) {
      const Vector3d v = tris[t].col(c);
      auto [it, fresh] = owner.insert({{v.x(), v.y(), v.z()}, t});
      if (!fresh) parent[find(t)] = find(it->second);
    }
  std::map<int, std::vector<int>> groups;
  for (int t = 0; t < int(tris.size()); ++t) groups[find(t)].push_back(t);
  std::vector<std::vector<int>> out;
  for (auto& [_, g] : groups) out.push_back(std::move(g));
  return out;
}

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

}  // namespace

std::vector<vector::Occluder> body_occluders(const sim::BodyModel& body, const sim::HeadPose& pose,
                                             const sim::Camera& camera, double bias) {
  const std::vector<Eigen::Matrix3d> tris = body.world_triangles(pose);
  std::vector<vector::Occluder> out;
  for (const std::vector<int>& group : surfaces(tris)) {
    std::vector<Eigen::Matrix3d> world;
    bool behind = false;
    for (int t : group) {
      world.push_back(tris[t]);
      for (int c = 0; c < 3; ++c)
        behind |= (Vector3d(tris[t].col(c)) - camera.eye).dot(camera.forward) <= 1e-3;
    }
    // A surface reaching behind the eye has no meaningful silhouette; it is left out.
    if (behind || world.empty()) continue;
    auto s = std::make_shared<const sim::SurfaceRays>(std::move(world), camera);
    std::vector<Vector2d> points;
    for (const auto& px : s->pixels()) points.insert(points.end(), px.begin(), px.end());
    vector::Occluder o;
    o.ring = convex_hull(points);
    if (o.ring.size() < 3) continue;
    o.depth = [s, bias](const Vector2d& p) { return s->depth(p) + bias; };
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace wisp::render
