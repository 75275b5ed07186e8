// Eye rays against projected, binned triangles (see surface_rays.hpp).
#include "sim/surface_rays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "sim/ray_triangle.hpp"

namespace wisp::sim {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// How far outside a triangle's projection, in pixels, a ray may still be tested against it: far
// above the rounding of the projection and of the 3D test.
constexpr double kMargin = 1e-4;

// The projected edges of triangle abc as lines n.p + c, n a unit normal pointing inwards (see
// SurfaceRays::edge_); zeros (every point passes) for a triangle whose projection is a sliver:
// twice its area below a millionth of its longest edge squared (a view of its plane within about
// 1e-6 radians of edge-on), where the 3D test divides by nearly 0.
std::array<double, 9> edge_lines(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const Vector2d corner[3] = {a, b, c};
  const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  const double longest2 =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (!(std::abs(area2) > 1e-6 * longest2)) return {};
  std::array<double, 9> out;
  for (int e = 0; e < 3; ++e) {
    const Vector2d p = corner[e], d = corner[(e + 1) % 3] - p;
    // Inwards is to the left of an edge of a triangle with area2 > 0, to the right otherwise.
    const Vector2d n = (area2 > 0 ? Vector2d(-d.y(), d.x()) : Vector2d(d.y(), -d.x())) / d.norm();
    out[3 * e] = n.x(), out[3 * e + 1] = n.y(), out[3 * e + 2] = -n.dot(p);
  }
  return out;
}

}  // namespace

SurfaceRays::SurfaceRays(std::vector<Vector3d> vertices, std::vector<Eigen::Vector3i> triangles,
                         const Camera& camera, bool with_folds,
                         std::shared_ptr<const EdgeNeighbours> neighbours)
    : vertex_(std::move(vertices)),
      triangle_(std::move(triangles)),
      camera_(camera),
      with_folds_(with_folds),
      neighbour_(std::move(neighbours)) {
  if (neighbour_ && neighbour_->size() != triangle_.size())
    throw std::invalid_argument("SurfaceRays: edge neighbours of another mesh");
  const size_t n = vertex_.size(), count = triangle_.size();
  for (const Eigen::Vector3i& t : triangle_)
    for (int c = 0; c < 3; ++c)
      if (t[c] < 0 || size_t(t[c]) >= n)
        throw std::invalid_argument("SurfaceRays: a triangle's corner is not a vertex");
  pixel_.resize(n);
  std::vector<char> ahead(n);
  for (size_t v = 0; v < n; ++v) {
    pixel_[v] = camera_.project(vertex_[v]);
    ahead[v] = (vertex_[v] - camera_.eye).dot(camera_.forward) > 1e-3;
  }
  // Per triangle its pixel box, which also makes the surface's, and its edges.
  box_.setEmpty();
  std::vector<std::array<double, 4>> bounds(count);  // x0, y0, x1, y1
  edge_.resize(count);
  for (size_t t = 0; t < count; ++t) {
    const Eigen::Vector3i& c = triangle_[t];
    Eigen::AlignedBox2d box;
    for (int k = 0; k < 3; ++k) box.extend(pixel_[size_t(c[k])]);
    box_.extend(box);
    bounds[t] = {box.min().x(), box.min().y(), box.max().x(), box.max().y()};
    const bool in_front = ahead[size_t(c[0])] && ahead[size_t(c[1])] && ahead[size_t(c[2])];
    edge_[t] = in_front
                   ? edge_lines(pixel_[size_t(c[0])], pixel_[size_t(c[1])], pixel_[size_t(c[2])])
                   : std::array<double, 9>{};
  }
  cells_ = std::clamp(int(std::sqrt(double(count))), 1, 64);
  first_.assign(size_t(cells_) * cells_ + 1, 0);
  if (box_.isEmpty()) return;
  const Vector2d extent = box_.sizes();
  scale_x_ = extent.x() > 0 ? cells_ / extent.x() : 0;
  scale_y_ = extent.y() > 0 ? cells_ / extent.y() : 0;
  // Each triangle in the cells its pixel box meets: the ranges found once, counted, then filled.
  std::vector<std::array<int, 4>> range(count);
  for (size_t t = 0; t < count; ++t) {
    const std::array<double, 4>& b = bounds[t];
    range[t] = {cell_x(b[0]), cell_y(b[1]), cell_x(b[2]), cell_y(b[3])};
    for (int y = range[t][1]; y <= range[t][3]; ++y)
      for (int x = range[t][0]; x <= range[t][2]; ++x) ++first_[size_t(y) * cells_ + x + 1];
  }
  for (size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
  binned_.resize(size_t(first_.back()));
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  for (size_t t = 0; t < count; ++t)
    for (int y = range[t][1]; y <= range[t][3]; ++y)
      for (int x = range[t][0]; x <= range[t][2]; ++x)
        binned_[size_t(fill[size_t(y) * cells_ + x]++)] = int(t);
}

EdgeNeighbours edge_neighbours(const std::vector<Vector3d>& vertices,
                               const std::vector<Eigen::Vector3i>& triangles) {
  // Vertices at one position get one id (the rank of the first of them in position order); an
  // edge is the pair of its corners' ids.
  const int nv = int(vertices.size());
  std::vector<int> by_position(size_t(nv), 0), id(size_t(nv), 0);
  for (int v = 0; v < nv; ++v) by_position[size_t(v)] = v;
  const auto before = [&](int a, int b) {
    const Vector3d &p = vertices[size_t(a)], &q = vertices[size_t(b)];
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  };
  std::sort(by_position.begin(), by_position.end(),
            [&](int a, int b) { return before(a, b) || (!before(b, a) && a < b); });
  for (int k = 0; k < nv; ++k) {
    const int v = by_position[size_t(k)], prev = k > 0 ? by_position[size_t(k - 1)] : -1;
    id[size_t(v)] =
        prev >= 0 && vertices[size_t(v)] == vertices[size_t(prev)] ? id[size_t(prev)] : k;
  }
  struct Use {
    std::uint64_t key;  // the edge's corner ids, lower first
    int use;            // 3 * triangle + edge
  };
  std::vector<Use> uses;
  uses.reserve(3 * triangles.size());
  for (int t = 0; t < int(triangles.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const std::uint64_t a = std::uint32_t(id[size_t(triangles[t][e])]),
                          b = std::uint32_t(id[size_t(triangles[t][(e + 1) % 3])]);
      uses.push_back({std::min(a, b) << 32 | std::max(a, b), 3 * t + e});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.key != y.key ? x.key < y.key : x.use < y.use;
  });
  EdgeNeighbours out(triangles.size(), {-1, -1, -1});
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 2) {
      const int u0 = uses[i].use, u1 = uses[i + 1].use;
      out[size_t(u0 / 3)][size_t(u0 % 3)] = u1;
      out[size_t(u1 / 3)][size_t(u1 % 3)] = u0;
    }
    i = j;
  }
  return out;
}

// Fold edges: on the mesh's border, shared by more than two triangles, or with both triangles on
// one side of the edge in the picture. Elsewhere the picture is covered on both sides of an edge.
void SurfaceRays::find_folds() const {
  if (!neighbour_)
    neighbour_ = std::make_shared<const EdgeNeighbours>(edge_neighbours(vertex_, triangle_));
  const EdgeNeighbours& across = *neighbour_;
  const auto apex_side = [&](int use, int other) {
    const Vector2d a = corner_pixel(use / 3, use % 3), b = corner_pixel(use / 3, (use % 3 + 1) % 3);
    const Vector2d apex = corner_pixel(other / 3, (other % 3 + 2) % 3);
    const Vector2d ab = b - a, ap = apex - a;
    return ab.x() * ap.y() - ab.y() * ap.x();
  };
  fold_.assign(triangle_.size(), {true, true, true});
  for (int t = 0; t < int(triangle_.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const int u0 = 3 * t + e, u1 = across[size_t(t)][size_t(e)];
      if (u1 < 0 || u1 < u0) continue;  // each pair once, from its lower use
      const bool fold = !(apex_side(u0, u0) * apex_side(u0, u1) < 0);
      fold_[size_t(t)][size_t(e)] = fold_[size_t(u1 / 3)][size_t(u1 % 3)] = fold;
    }
  fold_cell_.assign(first_.size() - 1, 0);
  for (size_t c = 0; c + 1 < first_.size(); ++c)
    for (int k = first_[c]; k < first_[c + 1] && !fold_cell_[c]; ++k) {
      const std::array<bool, 3>& f = fold_[size_t(binned_[size_t(k)])];
      fold_cell_[c] = f[0] || f[1] || f[2];
    }
}

int SurfaceRays::cell_x(double x) const {
  return std::clamp(int((x - box_.min().x()) * scale_x_), 0, cells_ - 1);
}

int SurfaceRays::cell_y(double y) const {
  return std::clamp(int((y - box_.min().y()) * scale_y_), 0, cells_ - 1);
}

Vector3d SurfaceRays::ray(const Vector2d& p) const {
  const Camera& c = camera_;
  return (c.forward + c.right * ((p.x() - 0.5 * c.width) / c.focal_px) -
          c.up * ((p.y() - 0.5 * c.height) / c.focal_px))
      .normalized();
}

double SurfaceRays::depth(const Vector2d& p) const {
  return first_hit(p).second;
}

std::pair<int, double> SurfaceRays::first_hit(const Vector2d& p) const {
  if (box_.isEmpty() || !box_.contains(p)) return {-1, INFINITY};
  const Vector3d dir = ray(p);
  double best = INFINITY;
  int hit = -1;
  const size_t c = size_t(cell_y(p.y())) * cells_ + cell_x(p.x());
  for (int k = first_[c]; k < first_[c + 1]; ++k) {
    const int t = binned_[size_t(k)];
    const std::array<double, 9>& e = edge_[size_t(t)];
    if (e[0] * p.x() + e[1] * p.y() + e[2] < -kMargin ||
        e[3] * p.x() + e[4] * p.y() + e[5] < -kMargin ||
        e[6] * p.x() + e[7] * p.y() + e[8] < -kMargin)
      continue;
    const double d = ray_triangle(camera_.eye, dir, corner(t, 0), corner(t, 1), corner(t, 2));
    if (d > 0 && d < best) best = d, hit = t;
  }
  return {hit, best};
}

namespace {

// Whether segment ab meets the closed box (Liang-Barsky clipping).
bool meets(const Vector2d& a, const Vector2d& b, const Eigen::AlignedBox2d& box) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 2; ++k) {
    const double d = b[k] - a[k];
    if (d == 0) {
      if (a[k] < box.min()[k] || a[k] > box.max()[k]) return false;
      continue;
    }
    double u = (box.min()[k] - a[k]) / d, v = (box.max()[k] - a[k]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

// A box that no fold edge meets lies wholly inside or outside the surface's projection: inside
// when the ray through its centre hits. Every ray through it then hits a triangle whose projection
// meets the box, at most as far as that triangle's plane is over the box. Along the unit ray
// u(p) = d(p) / |d(p)|, with d(p) affine in p, the plane n.(x - a) = 0 lies at
// h(p) = n.(a - eye) |d(p)| / n.d(p); over the box |d| (convex) is largest and n.d (affine)
// smallest at a corner, which bounds h when n.d > 0 at every corner.
double SurfaceRays::max_depth(const Eigen::AlignedBox2d& box) const {
  if (!with_folds_ || box_.isEmpty() || box.isEmpty() || !box_.contains(box)) return INFINITY;
  std::call_once(folds_found_, [this] { find_folds(); });
  const int start = first_hit(box.center()).first;
  if (start < 0) return INFINITY;
  const Camera& c = camera_;
  const Vector2d box_corner[4] = {box.min(), box.max(), Vector2d(box.min().x(), box.max().y()),
                                  Vector2d(box.max().x(), box.min().y())};
  Vector3d d[4];
  double longest = 0;
  for (int k = 0; k < 4; ++k) {
    d[k] = c.forward + c.right * ((box_corner[k].x() - 0.5 * c.width) / c.focal_px) -
           c.up * ((box_corner[k].y() - 0.5 * c.height) / c.focal_px);
    longest = std::max(longest, d[k].norm());
  }
  const auto meets_box = [&](int t) {
    Eigen::AlignedBox2d tb(corner_pixel(t, 0));
    tb.extend(corner_pixel(t, 1)), tb.extend(corner_pixel(t, 2));
    return tb.intersects(box);
  };
  // No fold of any layer meets the box.
  const int x0 = cell_x(box.min().x()), x1 = cell_x(box.max().x());
  const int y0 = cell_y(box.min().y()), y1 = cell_y(box.max().y());
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const size_t cell = size_t(y) * cells_ + x;
      if (!fold_cell_[cell]) continue;
      for (int k = first_[cell]; k < first_[cell + 1]; ++k)
        for (int t = binned_[size_t(k)], e = 0; e < 3; ++e)
          if (fold_[t][e] && meets(corner_pixel(t, e), corner_pixel(t, (e + 1) % 3), box))
            return INFINITY;
    }
  // The layer hit first through the centre covers the box: its triangles meeting the box, found
  // across shared edges from the centre's, bound the depth (the nearest hit is no farther).
  std::vector<int> layer = {start}, seen = {start};
  double worst = 0;
  for (size_t k = 0; k < layer.size(); ++k) {
    const int t = layer[k];
    const Vector3d &a = corner(t, 0), &b = corner(t, 1), &cc = corner(t, 2);
    Vector3d n = (b - a).cross(cc - a);
    double reach = n.dot(a - c.eye);
    if (reach < 0) n = -n, reach = -reach;
    double nearest = INFINITY;
    for (const Vector3d& dk : d) nearest = std::min(nearest, n.dot(dk));
    if (!(reach > 0 && nearest > 0)) return INFINITY;
    worst = std::max(worst, reach * longest / nearest);
    for (int across : (*neighbour_)[size_t(t)])
      if (const int u = across / 3;
          across >= 0 && std::find(seen.begin(), seen.end(), u) == seen.end()) {
        seen.push_back(u);
        if (meets_box(u)) layer.push_back(u);
      }
  }
  return worst > 0 ? worst * (1 + 1e-9) : INFINITY;
}

}  // namespace wisp::sim
