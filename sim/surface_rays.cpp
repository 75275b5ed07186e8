// Eye rays against projected, binned triangles (see surface_rays.hpp).
#include "sim/surface_rays.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "sim/ray_triangle.hpp"

namespace wisp::sim {

using Eigen::Vector2d;
using Eigen::Vector3d;

SurfaceRays::SurfaceRays(std::vector<Eigen::Matrix3d> triangles, const Camera& camera,
                         bool with_folds)
    : world_(std::move(triangles)), camera_(camera), with_folds_(with_folds) {
  box_.setEmpty();
  pixel_.reserve(world_.size());
  reach_.reserve(world_.size());
  constexpr double kMargin = 1e-4;  // pixels
  for (const Eigen::Matrix3d& t : world_) {
    std::array<Vector2d, 3> px;
    Eigen::AlignedBox2d b;
    bool ahead = true;
    for (int c = 0; c < 3; ++c) {
      px[c] = camera_.project(t.col(c));
      box_.extend(px[c]);
      b.extend(px[c]);
      ahead &= (t.col(c) - camera_.eye).dot(camera_.forward) > 1e-3;
    }
    pixel_.push_back(px);
    if (ahead)
      reach_.push_back({b.min().x() - kMargin, b.min().y() - kMargin, b.max().x() + kMargin,
                        b.max().y() + kMargin});
    else
      reach_.push_back({-INFINITY, -INFINITY, INFINITY, INFINITY});
  }
  cells_ = std::clamp(int(std::sqrt(double(world_.size()))), 1, 64);
  first_.assign(size_t(cells_) * cells_ + 1, 0);
  if (box_.isEmpty()) return;
  // Counted, then filled: each triangle in the cells its pixel box meets.
  const auto bin = [&](const auto& f) {
    for (int t = 0; t < int(pixel_.size()); ++t) {
      Eigen::AlignedBox2d b;
      for (const Vector2d& q : pixel_[t]) b.extend(q);
      for (int y = cell(b.min().y(), box_.min().y(), box_.max().y());
           y <= cell(b.max().y(), box_.min().y(), box_.max().y()); ++y)
        for (int x = cell(b.min().x(), box_.min().x(), box_.max().x());
             x <= cell(b.max().x(), box_.min().x(), box_.max().x()); ++x)
          f(size_t(y) * cells_ + x, t);
    }
  };
  bin([&](size_t c, int) { ++first_[c + 1]; });
  for (size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
  binned_.resize(size_t(first_.back()));
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  bin([&](size_t c, int t) { binned_[size_t(fill[c]++)] = t; });
}

// Fold edges: on the mesh's border, shared by more than two triangles, or with both triangles on
// one side of the edge in the picture. Elsewhere the picture is covered on both sides of an edge.
void SurfaceRays::find_folds() const {
  struct Use {
    std::array<double, 6> key;  // the edge's corners, lower first
    int use;                    // 3 * triangle + edge
  };
  std::vector<Use> uses;
  uses.reserve(3 * world_.size());
  for (int t = 0; t < int(world_.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const Vector3d a = world_[t].col(e), b = world_[t].col((e + 1) % 3);
      const bool lower =
          std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
      const Vector3d &u = lower ? a : b, &v = lower ? b : a;
      uses.push_back({{u.x(), u.y(), u.z(), v.x(), v.y(), v.z()}, 3 * t + e});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.key != y.key ? x.key < y.key : x.use < y.use;
  });
  fold_.assign(world_.size(), {true, true, true});
  neighbour_.assign(world_.size(), {-1, -1, -1});
  const auto apex_side = [&](int use, int other) {
    const Vector2d a = pixel_[use / 3][use % 3], b = pixel_[use / 3][(use % 3 + 1) % 3];
    const Vector2d apex = pixel_[other / 3][(other % 3 + 2) % 3];
    const Vector2d ab = b - a, ap = apex - a;
    return ab.x() * ap.y() - ab.y() * ap.x();
  };
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 2) {
      const int u0 = uses[i].use, u1 = uses[i + 1].use;
      const bool fold = !(apex_side(u0, u0) * apex_side(u0, u1) < 0);
      fold_[u0 / 3][u0 % 3] = fold_[u1 / 3][u1 % 3] = fold;
      neighbour_[u0 / 3][u0 % 3] = u1 / 3;
      neighbour_[u1 / 3][u1 % 3] = u0 / 3;
    }
    i = j;
  }
}

int SurfaceRays::cell(double v, double lo, double hi) const {
  return hi > lo ? std::clamp(int((v - lo) / (hi - lo) * cells_), 0, cells_ - 1) : 0;
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
  const size_t c = size_t(cell(p.y(), box_.min().y(), box_.max().y())) * cells_ +
                   cell(p.x(), box_.min().x(), box_.max().x());
  for (int k = first_[c]; k < first_[c + 1]; ++k) {
    const int t = binned_[size_t(k)];
    const std::array<double, 4>& r = reach_[size_t(t)];
    if (p.x() < r[0] || p.y() < r[1] || p.x() > r[2] || p.y() > r[3]) continue;
    const double d =
        ray_triangle(camera_.eye, dir, world_[t].col(0), world_[t].col(1), world_[t].col(2));
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
  const Vector2d corner[4] = {box.min(), box.max(), Vector2d(box.min().x(), box.max().y()),
                              Vector2d(box.max().x(), box.min().y())};
  Vector3d d[4];
  double longest = 0;
  for (int k = 0; k < 4; ++k) {
    d[k] = c.forward + c.right * ((corner[k].x() - 0.5 * c.width) / c.focal_px) -
           c.up * ((corner[k].y() - 0.5 * c.height) / c.focal_px);
    longest = std::max(longest, d[k].norm());
  }
  const auto meets_box = [&](int t) {
    const std::array<Vector2d, 3>& q = pixel_[t];
    Eigen::AlignedBox2d tb(q[0]);
    tb.extend(q[1]), tb.extend(q[2]);
    return tb.intersects(box);
  };
  // No fold of any layer meets the box.
  const int x0 = cell(box.min().x(), box_.min().x(), box_.max().x());
  const int x1 = cell(box.max().x(), box_.min().x(), box_.max().x());
  const int y0 = cell(box.min().y(), box_.min().y(), box_.max().y());
  const int y1 = cell(box.max().y(), box_.min().y(), box_.max().y());
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      for (int k = first_[size_t(y) * cells_ + x]; k < first_[size_t(y) * cells_ + x + 1]; ++k)
        for (int t = binned_[size_t(k)], e = 0; e < 3; ++e)
          if (fold_[t][e] && meets(pixel_[t][e], pixel_[t][(e + 1) % 3], box)) return INFINITY;
  // The layer hit first through the centre covers the box: its triangles meeting the box, found
  // across shared edges from the centre's, bound the depth (the nearest hit is no farther).
  std::vector<int> layer = {start}, seen = {start};
  double worst = 0;
  for (size_t k = 0; k < layer.size(); ++k) {
    const int t = layer[k];
    const Eigen::Matrix3d& w = world_[t];
    Vector3d n = (w.col(1) - w.col(0)).cross(w.col(2) - w.col(0));
    double reach = n.dot(w.col(0) - c.eye);
    if (reach < 0) n = -n, reach = -reach;
    double nearest = INFINITY;
    for (const Vector3d& dk : d) nearest = std::min(nearest, n.dot(dk));
    if (!(reach > 0 && nearest > 0)) return INFINITY;
    worst = std::max(worst, reach * longest / nearest);
    for (int u : neighbour_[t])
      if (u >= 0 && std::find(seen.begin(), seen.end(), u) == seen.end()) {
        seen.push_back(u);
        if (meets_box(u)) layer.push_back(u);
      }
  }
  return worst > 0 ? worst * (1 + 1e-9) : INFINITY;
}

}  // namespace wisp::sim
