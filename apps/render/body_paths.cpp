// Seamless tone regions of the body's surfaces (see body_paths.hpp).
#include "apps/render/body_paths.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace wisp::render {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// The two levels cutting a surface: where it leaves the solids drawn before it, and the shade.
enum Level : int { kCut = 0, kShade = 1 };

// The identity of a piece's corner, shared by every piece that has it:
//  - a mesh vertex i:                      (i, -1, 0)
//  - level l crossing mesh edge i < j:     (i, j, l)
//  - both levels crossing inside triangle t: (-1 - t, -1, 0)
struct Key {
  int a = 0, b = -1, c = 0;
  bool operator==(const Key& o) const { return a == o.a && b == o.b && c == o.c; }
  bool on_level(int l) const { return (b >= 0 && c == l) || a < 0; }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return std::hash<long long>()((static_cast<long long>(k.a) * 1000003 + k.b) * 4 + k.c);
  }
};

// A corner during clipping: its identity and barycentric coordinates in its triangle.
struct Corner {
  Key key;
  Vector3d w;
};

// The pieces of one surface: corners shared by identity, and each piece as a loop of corner
// indices, in the image orientation of front faces.
class Pieces {
 public:
  Pieces(const sim::ProjectedSurface& s, float threshold) : s_(s) {
    // Level values per vertex, nudged off zero so no vertex lies exactly on a level (every
    // crossing is then strictly inside an edge, and a corner is on one side or on the level).
    for (int l : {kCut, kShade}) {
      g_[l].resize(s.pixel.size());
      for (std::size_t v = 0; v < s.pixel.size(); ++v) {
        // (An infinite clearance, nothing drawn before, would make 0 * inf in the barycentric
        // interpolation.)
        const double g =
            l == kCut ? std::min(double(s.clearance[v]), 1e6) : double(s.shade[v]) - threshold;
        g_[l][v] = std::abs(g) < 1e-9 ? 1e-9 : g;
      }
    }
    for (std::size_t t = 0; t < s.triangles.size(); ++t) split(int(t));
  }

  std::vector<Vector2d> point;
  std::vector<std::vector<int>> lit, shadow;
  std::vector<Key> key;

 private:
  const sim::ProjectedSurface& s_;
  std::vector<double> g_[2];
  std::unordered_map<Key, int, KeyHash> index_;
  int tri_ = 0;

  int id(const Key& k, const Vector2d& p) {
    auto [it, fresh] = index_.emplace(k, int(point.size()));
    if (fresh) {
      point.push_back(p);
      key.push_back(k);
    }
    return it->second;
  }

  const Eigen::Vector3i& corners() const { return s_.triangles[tri_]; }
  double level(int l, const Corner& c) const {
    const Eigen::Vector3i& t = corners();
    return c.w[0] * g_[l][t[0]] + c.w[1] * g_[l][t[1]] + c.w[2] * g_[l][t[2]];
  }
  // -1 below, +1 above level l, 0 on it.
  int side(int l, const Corner& c) const {
    if (c.key.on_level(l)) return 0;
    return level(l, c) >= 0 ? 1 : -1;
  }

  // Where level l crosses the segment between corners u and v (on opposite sides).
  Corner crossing(int l, const Corner& u, const Corner& v) {
    const Eigen::Vector3i& t = corners();
    for (int k = 0; k < 3; ++k) {
      if (u.w[k] != 0 || v.w[k] != 0) continue;
      // Both on the mesh edge opposite corner k: computed from that edge alone, lowest vertex
      // first, so the triangle on the other side finds the same point.
      int i = (k + 1) % 3, j = (k + 2) % 3;
      if (t[i] > t[j]) std::swap(i, j);
      const double gi = g_[l][t[i]], gj = g_[l][t[j]];
      const double f = gi / (gi - gj);
      Corner c;
      c.key = Key{t[i], t[j], l};
      c.w = Vector3d::Zero();
      c.w[i] = 1 - f;
      c.w[j] = f;
      id(c.key, s_.pixel[t[i]] + f * (s_.pixel[t[j]] - s_.pixel[t[i]]));
      return c;
    }
    // Otherwise the segment runs along the other level inside the triangle: both levels cross
    // there, at the one point where both linear fields vanish.
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k) m.col(k) << g_[kCut][t[k]], g_[kShade][t[k]], 1.0;
    Corner c;
    c.key = Key{-1 - tri_, -1, 0};
    c.w = m.colPivHouseholderQr().solve(Vector3d(0, 0, 1));
    id(c.key, c.w[0] * s_.pixel[t[0]] + c.w[1] * s_.pixel[t[1]] + c.w[2] * s_.pixel[t[2]]);
    return c;
  }

  // Sutherland-Hodgman: the part of `poly` on side `keep` of level l (corners on it are kept).
  std::vector<Corner> clip(const std::vector<Corner>& poly, int l, int keep) {
    std::vector<Corner> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Corner& u = poly[i];
      const Corner& v = poly[(i + 1) % poly.size()];
      const int su = side(l, u), sv = side(l, v);
      if (su != -keep) out.push_back(u);
      if (su * sv < 0) out.push_back(crossing(l, u, v));
    }
    return out;
  }

  void split(int t) {
    tri_ = t;
    const Eigen::Vector3i& tri = corners();
    std::vector<Corner> poly;
    for (int k = 0; k < 3; ++k) {
      Corner c{Key{tri[k], -1, 0}, Vector3d::Zero()};
      c.w[k] = 1;
      id(c.key, s_.pixel[tri[k]]);
      poly.push_back(c);
    }
    poly = clip(poly, kCut, 1);
    if (poly.size() < 3) return;
    for (auto [keep, out] : {std::make_pair(1, &lit), std::make_pair(-1, &shadow)}) {
      const std::vector<Corner> piece = clip(poly, kShade, keep);
      if (piece.size() < 3) continue;
      std::vector<int> loop;
      for (const Corner& c : piece) loop.push_back(index_.at(c.key));
      out->push_back(std::move(loop));
    }
  }
};

// The outline of a union of same-turning pieces: their edges, minus every edge that another
// piece traverses the other way, chained into loops of corner indices.
std::vector<std::vector<int>> outline(
    const std::vector<const std::vector<std::vector<int>>*>& sets) {
  std::map<std::pair<int, int>, int> count;  // directed edge -> net uses
  for (const auto* set : sets)
    for (const std::vector<int>& piece : *set)
      for (std::size_t i = 0; i < piece.size(); ++i) {
        const int a = piece[i], b = piece[(i + 1) % piece.size()];
        if (a == b) continue;
        auto twin = count.find({b, a});
        if (twin != count.end() && twin->second > 0) {
          if (--twin->second == 0) count.erase(twin);
        } else {
          ++count[{a, b}];
        }
      }
  std::multimap<int, int> next;  // start -> end, one entry per remaining use
  for (const auto& [edge, n] : count)
    for (int k = 0; k < n; ++k) next.emplace(edge.first, edge.second);
  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    auto it = next.begin();
    const int start = it->first;
    std::vector<int> loop{start};
    int at = it->second;
    next.erase(it);
    while (at != start) {
      loop.push_back(at);
      it = next.find(at);
      if (it == next.end()) break;  // cannot happen for closed outlines; drop the remainder
      at = it->second;
      next.erase(it);
    }
    if (at == start && loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

// A polygon as a closed path of straight cubics.
std::vector<Vector2d> polygon_path(const std::vector<int>& loop, const std::vector<Vector2d>& p) {
  std::vector<Vector2d> out{p[loop[0]]};
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vector2d& a = p[loop[i]];
    const Vector2d& b = p[loop[(i + 1) % loop.size()]];
    out.push_back(a + (b - a) / 3);
    out.push_back(a + 2 * (b - a) / 3);
    out.push_back(b);
  }
  return out;
}

}  // namespace

std::vector<BodyPath> body_paths(const sim::ProjectedBody& body, const BodyTones& tones) {
  std::vector<BodyPath> out;
  for (const sim::ProjectedSurface& s : body.surfaces) {
    const Pieces pieces(s, tones.threshold);
    for (bool shadow : {false, true}) {
      const auto loops =
          shadow ? outline({&pieces.shadow}) : outline({&pieces.lit, &pieces.shadow});
      if (loops.empty()) continue;
      BodyPath path;
      path.part = s.part;
      path.shadow = shadow;
      path.color = shadow ? tones.shadow : tones.lit;
      for (const std::vector<int>& loop : loops)
        path.loops.push_back(polygon_path(loop, pieces.point));
      out.push_back(std::move(path));
    }
  }
  return out;
}

}  // namespace wisp::render
