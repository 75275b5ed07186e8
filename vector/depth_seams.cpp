// Depth seams between overlapping wisps (vector/depth_seams.hpp).
//
// A wisp's depth is affine over each triangle of its band (vector/band_depth.hpp), so over a pair
// of triangles of two wisps the points of equal depth are the zero line of an affine map, and the
// seam piece is that line clipped to both triangles (both convex). A piece ends on an edge of one
// of the triangles. There the depth of that triangle's wisp is the linear interpolation of the
// edge's two corner depths, which the neighbouring triangle across the edge shares; the point is
// computed from the edge's corners in a fixed order and the other wisp's affine map, so the piece
// of the neighbouring pair that continues the seam starts at the same point, bit for bit, and the
// seam has no gap (a gap would leave the face it runs through whole). Where a piece ends on a
// side of a band, which is an outline segment of the arrangement's input, it is lengthened by
// kOvershoot to cross that segment rather than stop a rounding error short of it.
#include "vector/depth_seams.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>

#include "vector/band_depth.hpp"
#include "vector/buckets.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

constexpr double kOvershoot = 1e-4;  // px; the arrangement snaps to 2^-17 px at 1024 px

// A triangle of a wisp's band, with which of its edges (v[k] -> v[k + 1]) lie on the outline.
struct Triangle {
  CellTriangle t;
  int wisp = 0;
  std::array<bool, 3> outline{};
  Eigen::AlignedBox2d box;
  double lo = 0, hi = 0;  // its depth range
};

// The outline edges of a cell's triangles: the band's sides, and the first and last sections
// (root and tip caps). Corners are compared exactly: they are copies of the sections' points.
void mark_outline(Triangle& tri, const Wisp& w, int cell) {
  const Section &a = w.sections[cell], &b = w.sections[cell + 1];
  const bool first = cell == 0, last = cell + 2 == int(w.sections.size());
  const auto is = [](const Vector2d& p, const Vector2d& q, const Vector2d& u, const Vector2d& v) {
    return (p == u && q == v) || (p == v && q == u);
  };
  for (int k = 0; k < 3; ++k) {
    const Vector2d &p = tri.t.v[k], &q = tri.t.v[(k + 1) % 3];
    tri.outline[k] = is(p, q, a.left, b.left) || is(p, q, a.right, b.right) ||
                     (first && is(p, q, a.left, a.right)) || (last && is(p, q, b.left, b.right));
  }
}

// Where the line f = 0 crosses edge (u, v), f being fu at u and fv at v: computed from the corners
// in lexicographic order, so that both triangles sharing the edge get the same point.
Vector2d crossing(Vector2d u, Vector2d v, double fu, double fv) {
  if (v.x() < u.x() || (v.x() == u.x() && v.y() < u.y())) std::swap(u, v), std::swap(fu, fv);
  return u + (v - u) * (fu / (fu - fv));
}

struct End {
  Vector2d p;
  double along = 0;  // position along the seam line
  bool outline = false;
};

// The two points where the zero line of (depth of `mine` - depth of `other`) crosses the edges of
// `mine`, or false. On mine's edges its depth is the corners' interpolation, not its affine map.
bool clip(const Triangle& mine, const Triangle& other, bool mine_first, const Vector2d& dir,
          std::array<End, 2>& out) {
  const auto f = [&](int k) {
    const double d = mine.t.z[k] - other.t.depth(mine.t.v[k]);
    return mine_first ? d : -d;
  };
  const double fk[3] = {f(0), f(1), f(2)};
  int n = 0;  // the sign changes around a triangle: none or two
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if ((fk[k] > 0) == (fk[l] > 0)) continue;
    const Vector2d p = crossing(mine.t.v[k], mine.t.v[l], fk[k], fk[l]);
    out[n++] = {p, p.dot(dir), mine.outline[k]};
  }
  if (n != 2) return false;
  if (out[1].along < out[0].along) std::swap(out[0], out[1]);
  return true;
}

// The seam piece of triangles a and b (a of the lower wisp), if any.
void seam_piece(const Triangle& a, const Triangle& b, int seam_id,
                std::vector<OutlineSegment>& out) {
  const Vector2d g = a.t.grad - b.t.grad;
  // Parallel planes: equal everywhere (duplicates, left to the index rule) or nowhere.
  if (!(g.squaredNorm() > 0)) return;
  const Vector2d dir = Vector2d(-g.y(), g.x()).normalized();
  std::array<End, 2> ea, eb;
  if (!clip(a, b, true, dir, ea) || !clip(b, a, false, dir, eb)) return;
  const End& e0 = ea[0].along >= eb[0].along ? ea[0] : eb[0];
  const End& e1 = ea[1].along <= eb[1].along ? ea[1] : eb[1];
  if (!(e1.along > e0.along)) return;
  const Vector2d p0 = e0.outline ? Vector2d(e0.p - kOvershoot * dir) : e0.p;
  const Vector2d p1 = e1.outline ? Vector2d(e1.p + kOvershoot * dir) : e1.p;
  out.push_back({p0, p1, seam_id});
}

// The piece of triangle `tri` between the two of its edges where `behind` changes from one corner
// to the next, at the points cross(k, l) gives for edge (k, l), if any.
template <class Cross>
void change_piece(const Triangle& tri, const std::array<bool, 3>& behind, Cross&& cross,
                  int seam_id, std::vector<OutlineSegment>& out) {
  std::array<Vector2d, 2> p;
  std::array<bool, 2> outline{};
  int n = 0;  // the changes around a triangle: none or two
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if (behind[k] == behind[l]) continue;
    p[n] = cross(k, l);
    outline[n++] = tri.outline[k];
  }
  if (n != 2 || p[0] == p[1]) return;
  const Vector2d dir = (p[1] - p[0]).normalized();
  out.push_back({outline[0] ? Vector2d(p[0] - kOvershoot * dir) : p[0],
                 outline[1] ? Vector2d(p[1] + kOvershoot * dir) : p[1], seam_id});
}

// Where the eye rays through segment (u, v) stop meeting an occluder that they meet at u and miss
// at v, to 2^-8 of the segment, found from the corners in lexicographic order so that both
// triangles sharing the edge get the same point.
Vector2d silhouette_on(Vector2d u, Vector2d v, bool hit_at_u,
                       const std::function<double(const Vector2d&)>& depth) {
  if (v.x() < u.x() || (v.x() == u.x() && v.y() < u.y())) std::swap(u, v), hit_at_u = !hit_at_u;
  double hit = hit_at_u ? 0 : 1, miss = 1 - hit;
  for (int i = 0; i < 8; ++i) {
    const double mid = 0.5 * (hit + miss);
    (std::isfinite(depth(u + mid * (v - u))) ? hit : miss) = mid;
  }
  return u + 0.5 * (hit + miss) * (v - u);
}

// The seams between the triangles `tris` (of their wisps, in wisp order) and the occluders
// (depth_seams.hpp).
void occluder_pieces(const std::vector<Wisp>& wisps, const std::vector<Triangle>& tris,
                     const std::vector<Occluder>& occluders, int seam_id,
                     std::vector<OutlineSegment>& out) {
  std::vector<Eigen::AlignedBox2d> rings;
  for (const Occluder& o : occluders) {
    Eigen::AlignedBox2d box;
    for (const Vector2d& p : o.ring) box.extend(p);
    rings.push_back(box);
  }
  // Per wisp and occluder, the occluder's depth at each section's two points (NaN: not cast yet),
  // and the silhouette points found on the edges between them: the corners of a wisp's triangles
  // are its sections' points, each shared by up to six triangles, each edge by two.
  std::vector<double> at;
  std::unordered_map<std::uint64_t, Vector2d> silhouettes;
  int at_wisp = -1;
  for (const Triangle& tri : tris) {
    const size_t points = 2 * wisps[tri.wisp].sections.size();
    if (tri.wisp != at_wisp) {
      at.assign(points * occluders.size(), NAN), at_wisp = tri.wisp;
      silhouettes.clear();
    }
    const std::array<int, 3>& key = tri.t.point;
    for (size_t k = 0; k < occluders.size(); ++k) {
      if (!rings[k].intersects(tri.box) || !occluders[k].depth) continue;
      std::array<double, 3> f;  // the wisp's depth minus the occluder's, NaN on a miss
      for (int c = 0; c < 3; ++c) {
        double& z = at[k * points + key[c]];
        if (std::isnan(z)) z = occluders[k].depth(tri.t.v[c]);
        f[c] = std::isfinite(z) ? tri.t.z[c] - z : NAN;
      }
      // The wisp is behind where the ray meets the occluder nearer; where it misses, the wisp is
      // in front, and the change lies at the occluder's silhouette (inside its ring, which is a
      // convex hull).
      const std::array<bool, 3> behind = {f[0] > 0, f[1] > 0, f[2] > 0};
      change_piece(
          tri, behind,
          [&](int a, int b) {
            if (!std::isnan(f[a]) && !std::isnan(f[b]))
              return crossing(tri.t.v[a], tri.t.v[b], f[a], f[b]);
            const std::uint64_t edge =
                (std::uint64_t(k) * points + std::min(key[a], key[b])) * points +
                std::max(key[a], key[b]);
            const auto [it, added] = silhouettes.try_emplace(edge);
            if (added)
              it->second =
                  silhouette_on(tri.t.v[a], tri.t.v[b], !std::isnan(f[a]), occluders[k].depth);
            return it->second;
          },
          seam_id, out);
    }
  }
}

}  // namespace

std::vector<OutlineSegment> depth_seams(const std::vector<Wisp>& wisps,
                                        const std::vector<char>& used,
                                        const std::vector<std::vector<char>>& hidden,
                                        const std::vector<Occluder>& occluders, int seam_id,
                                        const Eigen::AlignedBox2d& view) {
  std::vector<Triangle> tris;  // in wisp order
  Eigen::AlignedBox2d all;
  for (int w = 0; w < int(wisps.size()); ++w) {
    if (!used[w]) continue;
    for (int i = 0; i + 1 < int(wisps[w].sections.size()); ++i) {
      if (w < int(hidden.size()) && i < int(hidden[w].size()) && hidden[w][i]) continue;
      std::array<CellTriangle, 2> cell;
      if (!cell_triangles(wisps[w], i, cell)) continue;
      for (const CellTriangle& t : cell) {
        Triangle tri;
        tri.t = t, tri.wisp = w;
        tri.box = Eigen::AlignedBox2d(t.v[0]);
        tri.box.extend(t.v[1]), tri.box.extend(t.v[2]);
        if (!view.isEmpty() && !view.intersects(tri.box)) continue;
        const Vector2d e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
        if (e1.x() * e2.y() - e1.y() * e2.x() == 0) continue;  // no area
        tri.lo = std::min({t.z[0], t.z[1], t.z[2]}), tri.hi = std::max({t.z[0], t.z[1], t.z[2]});
        mark_outline(tri, wisps[w], i);
        all.extend(tri.box);
        tris.push_back(tri);
      }
    }
  }
  std::vector<OutlineSegment> seams;
  if (tris.empty()) return seams;

  // A uniform grid of squares about the size of a triangle; each pair is tested in the square of
  // its boxes' common corner. Within a square the triangles are sorted by their least depth, so
  // that each meets only those whose depth ranges overlap its own.
  double extent = 0;
  for (const Triangle& t : tris) extent += t.box.sizes().maxCoeff();
  const Vector2d size = all.sizes().cwiseMax(1e-9);
  // Not many more squares than triangles, whatever the spread (a huge triangle reaching into the
  // view, from a strand near the eye plane).
  double side = std::max(extent / double(tris.size()), 1e-6);
  while ((size.x() / side + 1) * (size.y() / side + 1) > 4.0 * double(tris.size()) + 1024)
    side *= 2;
  const int nx = int(size.x() / side) + 1, ny = int(size.y() / side) + 1;
  const auto col = [&](double x) { return std::clamp(int((x - all.min().x()) / side), 0, nx - 1); };
  const auto row = [&](double y) { return std::clamp(int((y - all.min().y()) / side), 0, ny - 1); };
  const Buckets<int> grid = bucket<int>(nx * ny, [&](const auto& put) {
    for (int i = 0; i < int(tris.size()); ++i)
      for (int y = row(tris[i].box.min().y()); y <= row(tris[i].box.max().y()); ++y)
        for (int x = col(tris[i].box.min().x()); x <= col(tris[i].box.max().x()); ++x)
          put(y * nx + x, i);
  });
  std::vector<int> order;
  for (int k = 0; k < nx * ny; ++k) {
    order.assign(grid.items.begin() + grid.begin[k], grid.items.begin() + grid.begin[k + 1]);
    std::sort(order.begin(), order.end(), [&](int i, int j) {
      return tris[i].lo != tris[j].lo ? tris[i].lo < tris[j].lo : i < j;
    });
    for (size_t u = 0; u < order.size(); ++u)
      for (size_t v = u + 1; v < order.size() && tris[order[v]].lo <= tris[order[u]].hi; ++v) {
        const int i = std::min(order[u], order[v]), j = std::max(order[u], order[v]);
        const Triangle &a = tris[i], &b = tris[j];  // in index order: a's wisp first
        if (a.wisp == b.wisp) continue;
        const Eigen::AlignedBox2d both = a.box.intersection(b.box);
        if (both.isEmpty() || row(both.min().y()) * nx + col(both.min().x()) != k) continue;
        seam_piece(a, b, seam_id, seams);
      }
  }
  occluder_pieces(wisps, tris, occluders, seam_id, seams);
  return seams;
}

}  // namespace wisp::vector
