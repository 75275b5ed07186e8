// Seamless tone regions of the body's surfaces, and the face's strokes (see body_paths.hpp).
#include "apps/render/body_paths.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "vector/buckets.hpp"
#include "vector/catmull_rom.hpp"
#include "vector/stroke_fit.hpp"

namespace wisp::render {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// The levels that cut a surface into pieces, each a per-vertex value interpolated linearly:
//  - kCut: the clearance from the solids drawn before; the surface shows where it is >= 0;
//  - kTerminator: shade - threshold; the shadow tone where it is < 0;
//  - kOffset: the terminator's value over its image gradient, plus `band` px: about the pixel
//    distance from the terminator, >= 0 up to `band` px into the shadow.
enum Level : int { kCut = 0, kTerminator = 1, kOffset = 2, kLevels = 3 };

// The identity of a piece's corner, shared by every piece that has it:
//  - a mesh vertex i:                            (i, -1, 0)
//  - level l crossing mesh edge i < j:           (i, j, l)
//  - levels l1 < l2 crossing inside triangle t:  (-1 - t, l1, l2)
struct Key {
  int a = 0, b = -1, c = 0;
  bool operator==(const Key& o) const { return a == o.a && b == o.b && c == o.c; }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return std::hash<long long>()((static_cast<long long>(k.a) * 1000003 + k.b) * 4 + k.c);
  }
};

// A corner during clipping: its identity, the levels it lies on (bits) and its barycentric
// coordinates in its triangle.
struct Corner {
  Key key;
  int on = 0;
  Vector3d w;
};

// A piece of a triangle while it is clipped, on the stack: each of the three clips at most
// doubles the corners (a corner and a crossing per edge), so 3 * 2^3 always fit.
struct Polygon {
  std::array<Corner, 24> corner;
  int size = 0;
  void push_back(const Corner& c) { corner[size++] = c; }
};

// Loops of corner indices, one after another in one array (a surface has tens of thousands of
// pieces: a vector each was most of their cost).
struct Loops {
  std::vector<int> first{0};  // loop i is corner[first[i]] .. corner[first[i + 1] - 1]
  std::vector<int> corner;

  int size() const { return int(first.size()) - 1; }
  template <class Each>
  void for_each_edge(int i, Each&& each) const {  // each(a, b) for every edge a -> b of loop i
    const int b = first[size_t(i)], e = first[size_t(i) + 1];
    for (int k = b; k < e; ++k) each(corner[size_t(k)], corner[size_t(k + 1 < e ? k + 1 : b)]);
  }
};

// The pieces of one surface in the image orientation of front faces, as loops of corner indices
// (corners shared by identity): lit (terminator >= 0), band (between the terminator and the
// offset), deep (shadow beyond the offset).
class Pieces {
 public:
  Pieces(const sim::ProjectedSurface& s, float threshold, double band_width) : s_(s) {
    const std::size_t n = s.pixel.size();
    // The shade's image gradient per vertex: the area-weighted mean over its front faces.
    std::vector<double> gradient(n, 0.0), weight(n, 0.0);
    for (const Eigen::Vector3i& t : s.triangles) {
      const Vector2d e1 = s.pixel[t[1]] - s.pixel[t[0]], e2 = s.pixel[t[2]] - s.pixel[t[0]];
      const double det = e1.x() * e2.y() - e1.y() * e2.x();
      if (std::abs(det) < 1e-12) continue;
      const double d1 = s.shade[t[1]] - s.shade[t[0]], d2 = s.shade[t[2]] - s.shade[t[0]];
      const Vector2d g((d1 * e2.y() - d2 * e1.y()) / det, (d2 * e1.x() - d1 * e2.x()) / det);
      for (int k = 0; k < 3; ++k) {
        gradient[t[k]] += std::abs(det) * g.norm();
        weight[t[k]] += std::abs(det);
      }
    }
    for (int l = 0; l < kLevels; ++l) g_[l].resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      const double shade = double(s.shade[v]) - threshold;
      const double slope = weight[v] > 0 ? std::max(gradient[v] / weight[v], 1e-6) : 1.0;
      // (An infinite clearance, nothing drawn before, would make 0 * inf in the barycentric
      // interpolation.)
      const double value[kLevels] = {std::min(double(s.clearance[v]), 1e6), shade,
                                     shade / slope + band_width};
      // Nudged off zero: no vertex lies exactly on a level, so every crossing is strictly inside
      // an edge, and a corner is on one side of a level or on it.
      for (int l = 0; l < kLevels; ++l) g_[l][v] = std::abs(value[l]) < 1e-9 ? 1e-9 : value[l];
    }
    vertex_index_.assign(n, -1);
    for (std::size_t t = 0; t < s.triangles.size(); ++t) split(int(t));
  }

  std::vector<Vector2d> point;
  std::vector<int> on;  // per corner: the levels it lies on (bits)
  std::vector<Key> key;
  Loops lit, band, deep;

 private:
  const sim::ProjectedSurface& s_;
  std::vector<double> g_[kLevels];
  // Corner indices by identity: mesh vertices (most corners) in an array, crossings in a map.
  std::vector<int> vertex_index_;
  std::unordered_map<Key, int, KeyHash> index_;
  int tri_ = 0;

  int id(const Corner& c, const Vector2d& p) {
    const bool vertex = c.key.a >= 0 && c.key.b < 0;
    int& slot = vertex ? vertex_index_[c.key.a] : index_.emplace(c.key, -1).first->second;
    if (slot < 0) {
      slot = int(point.size());
      point.push_back(p);
      on.push_back(c.on);
      key.push_back(c.key);
    }
    return slot;
  }
  int index(const Key& k) const { return k.a >= 0 && k.b < 0 ? vertex_index_[k.a] : index_.at(k); }

  const Eigen::Vector3i& corners() const { return s_.triangles[tri_]; }
  // -1 below, +1 above level l, 0 on it.
  int side(int l, const Corner& c) const {
    if (c.on & (1 << l)) return 0;
    const Eigen::Vector3i& t = corners();
    return c.w[0] * g_[l][t[0]] + c.w[1] * g_[l][t[1]] + c.w[2] * g_[l][t[2]] >= 0 ? 1 : -1;
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
      Corner c{Key{t[i], t[j], l}, 1 << l, Vector3d::Zero()};
      c.w[i] = 1 - f;
      c.w[j] = f;
      id(c, s_.pixel[t[i]] + f * (s_.pixel[t[j]] - s_.pixel[t[i]]));
      return c;
    }
    // Otherwise the segment runs along another level inside the triangle: both levels cross
    // there, at the one point where both linear fields vanish.
    const int shared = u.on & v.on & ~(1 << l);
    int other = 0;
    while (other < kLevels && !(shared & (1 << other))) ++other;
    const int l1 = std::min(l, other), l2 = std::max(l, other);
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k) m.col(k) << g_[l1][t[k]], g_[l2][t[k]], 1.0;
    Corner c{Key{-1 - tri_, l1, l2}, (1 << l1) | (1 << l2), Vector3d::Zero()};
    c.w = m.colPivHouseholderQr().solve(Vector3d(0, 0, 1));
    id(c, c.w[0] * s_.pixel[t[0]] + c.w[1] * s_.pixel[t[1]] + c.w[2] * s_.pixel[t[2]]);
    return c;
  }

  // Sutherland-Hodgman: the part of `poly` on side `keep` of level l (corners on it are kept).
  Polygon clip(const Polygon& poly, int l, int keep) {
    Polygon out;
    for (int i = 0; i < poly.size; ++i) {
      const Corner& u = poly.corner[i];
      const Corner& v = poly.corner[(i + 1) % poly.size];
      const int su = side(l, u), sv = side(l, v);
      if (su != -keep) out.push_back(u);
      if (su * sv < 0) out.push_back(crossing(l, u, v));
    }
    return out;
  }

  void keep(const Polygon& piece, Loops& out) {
    if (piece.size < 3) return;
    for (int i = 0; i < piece.size; ++i) out.corner.push_back(index(piece.corner[i].key));
    out.first.push_back(int(out.corner.size()));
  }

  // +1 when the triangle's corners are all on or above level l, -1 when all below, else 0: a
  // corner's side, side() at its barycentric unit vector, is its value's sign.
  int one_side(int l) const {
    const Eigen::Vector3i& t = corners();
    const bool a = g_[l][t[0]] >= 0, b = g_[l][t[1]] >= 0, c = g_[l][t[2]] >= 0;
    return a == b && b == c ? (a ? 1 : -1) : 0;
  }

  void split(int t) {
    tri_ = t;
    const Eigen::Vector3i& tri = corners();
    Polygon poly;
    for (int k = 0; k < 3; ++k) {
      Corner c{Key{tri[k], -1, 0}, 0, Vector3d::Unit(k)};
      id(c, s_.pixel[tri[k]]);
      poly.push_back(c);
    }
    // Most triangles lie wholly on one side of each level: the clips below would keep them whole
    // in one set, or drop them, with no crossing.
    const int cut = one_side(kCut);
    if (cut < 0) return;
    if (cut > 0) {
      const int terminator = one_side(kTerminator), offset = one_side(kOffset);
      Loops* whole = terminator > 0                 ? &lit
                     : terminator < 0 && offset > 0 ? &band
                     : terminator < 0 && offset < 0 ? &deep
                                                    : nullptr;
      if (whole) {
        keep(poly, *whole);
        return;
      }
    }
    poly = clip(poly, kCut, 1);
    if (poly.size < 3) return;
    keep(clip(poly, kTerminator, 1), lit);
    const Polygon shadow = clip(poly, kTerminator, -1);
    if (shadow.size < 3) return;
    keep(clip(shadow, kOffset, 1), band);
    keep(clip(shadow, kOffset, -1), deep);
  }
};

// The outline of a union of same-turning pieces: their edges, minus every edge that another
// piece traverses the other way, chained into loops of corner indices (`corners` of them). Each
// loop starts at the lowest corner with an edge left and, where a corner has several, follows
// the one to the lowest corner first.
std::vector<std::vector<int>> outline(const std::vector<const Loops*>& sets, int corners) {
  // Each edge {lo, hi} once with its net uses (+1 per traversal from lo, -1 per one from hi),
  // in buckets by lo.
  struct Use {
    int hi, net;
  };
  vector::Buckets<Use> uses = vector::bucket<Use>(corners, [&](const auto& put) {
    for (const Loops* set : sets)
      for (int i = 0; i < set->size(); ++i)
        set->for_each_edge(i, [&](int a, int b) {
          if (a != b) put(std::min(a, b), Use{std::max(a, b), a < b ? 1 : -1});
        });
  });
  // The edges left, directed the way their net uses go.
  struct Edge {
    int from, to, count;
  };
  std::vector<Edge> left;
  for (int lo = 0; lo < corners; ++lo) {
    const auto b = uses.items.begin() + uses.begin[lo], e = uses.items.begin() + uses.begin[lo + 1];
    std::sort(b, e, [](const Use& x, const Use& y) { return x.hi < y.hi; });
    for (auto it = b; it != e;) {
      int net = 0;
      const int hi = it->hi;
      for (; it != e && it->hi == hi; ++it) net += it->net;
      if (net > 0) left.push_back({lo, hi, net});
      if (net < 0) left.push_back({hi, lo, -net});
    }
  }
  // Their ends in buckets by their start, each bucket in order.
  vector::Buckets<int> edges = vector::bucket<int>(corners, [&](const auto& put) {
    for (const Edge& e : left)
      for (int k = 0; k < e.count; ++k) put(e.from, e.to);
  });
  for (int c = 0; c < corners; ++c)
    std::sort(edges.items.begin() + edges.begin[c], edges.items.begin() + edges.begin[c + 1]);
  const std::vector<int>& start = edges.begin;
  const std::vector<int>& to = edges.items;
  // next[c]: corner c's first edge not yet followed (each corner's edges go in order).
  std::vector<int> next(start.begin(), start.end() - 1);
  std::vector<std::vector<int>> loops;
  int from = 0;  // the lowest corner that may have an edge left
  for (;;) {
    while (from < corners && next[from] == start[from + 1]) ++from;
    if (from == corners) break;
    std::vector<int> loop{from};
    int at = to[next[from]++];
    while (at != from) {
      loop.push_back(at);
      if (next[at] == start[at + 1]) break;  // cannot happen for closed outlines; drop the rest
      at = to[next[at]++];
    }
    if (at == from && loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

// What an outline edge runs along: a mesh edge (the silhouette: front faces meet back faces) or
// a level (the cut, the terminator, the offset).
int kind(const Pieces& p, int a, int b) {
  const Key &ka = p.key[a], &kb = p.key[b];
  // Two crossings of one mesh edge (of different levels) lie along that edge.
  if (ka.b >= 0 && kb.b >= 0 && ka.a >= 0 && ka.a == kb.a && ka.b == kb.b) return -1;
  const int shared = p.on[a] & p.on[b];
  for (int l = 0; l < kLevels; ++l)
    if (shared & (1 << l)) return l;
  return -1;
}

// An outline loop as closed cubics: cut into runs where the kind of edge changes or at a
// junction, each run fitted on its own. The same run in two regions' outlines (the silhouette
// where it bounds both fills) is the same sequence of corners, so it becomes the same cubics.
std::vector<Vector2d> fitted_loop(const std::vector<int>& loop, const Pieces& p,
                                  const std::vector<char>& junction, double tolerance) {
  const std::size_t n = loop.size();
  std::vector<int> edge_kind(n);
  for (std::size_t i = 0; i < n; ++i) edge_kind[i] = kind(p, loop[i], loop[(i + 1) % n]);
  const auto breaks = [&](std::size_t i) {  // at corner i, between edges i - 1 and i
    return junction[loop[i]] || edge_kind[(i + n - 1) % n] != edge_kind[i];
  };
  std::size_t first = n;
  for (std::size_t i = 0; i < n && first == n; ++i)
    if (breaks(i)) first = i;
  vector::FitOptions options;
  options.tolerance = tolerance;
  options.corner_deg = 60;  // a smooth surface's outline bends gently; sharper turns are real
  if (first == n) {         // one smooth closed curve
    std::vector<Vector2d> pts;
    for (int c : loop) pts.push_back(p.point[c]);
    return vector::fit_cubics(pts, options, true).points;
  }
  std::vector<Vector2d> out{p.point[loop[first]]};
  for (std::size_t start = first, done = 0; done < n;) {
    std::vector<Vector2d> run{p.point[loop[start]]};
    std::size_t i = start;
    do {
      i = (i + 1) % n;
      run.push_back(p.point[loop[i]]);
      ++done;
    } while (!breaks(i) && done < n);
    const std::vector<Vector2d> cubics = vector::fit_cubics(run, options).points;
    if (cubics.size() >= 4) out.insert(out.end(), cubics.begin() + 1, cubics.end());
    start = i;
  }
  return out;
}

// The feature's name, for its stroke's SVG id.
const char* feature_name(sim::Feature f) {
  switch (f) {
    case sim::Feature::Brow:
      return "brow";
    case sim::Feature::Lid:
      return "lid";
    case sim::Feature::Iris:
      return "iris";
    case sim::Feature::Nose:
      return "nose";
    case sim::Feature::Mouth:
      return "mouth";
  }
  return "line";
}

}  // namespace

std::vector<BodyPath> body_paths(const sim::ProjectedBody& body, const BodyTones& tones) {
  std::vector<BodyPath> out;
  for (const sim::ProjectedSurface& s : body.surfaces) {
    const Pieces pieces(s, tones.threshold, tones.overlap);
    const int corners = int(pieces.point.size());
    const auto lit = outline({&pieces.lit, &pieces.band}, corners);
    const auto shadow = outline({&pieces.band, &pieces.deep}, corners);
    // Junctions: where either outline turns from one kind of edge to another; both break there,
    // so the silhouette they share is cut into the same runs.
    std::vector<char> junction(pieces.point.size(), 0);
    for (const auto* loops : {&lit, &shadow})
      for (const std::vector<int>& loop : *loops)
        for (std::size_t i = 0, n = loop.size(); i < n; ++i)
          if (kind(pieces, loop[(i + n - 1) % n], loop[i]) !=
              kind(pieces, loop[i], loop[(i + 1) % n]))
            junction[loop[i]] = 1;
    for (bool dark : {false, true}) {
      const auto& loops = dark ? shadow : lit;
      if (loops.empty()) continue;
      BodyPath path;
      path.part = s.part;
      path.shadow = dark;
      path.color = dark ? tones.shadow : tones.lit;
      for (const std::vector<int>& loop : loops)
        path.loops.push_back(fitted_loop(loop, pieces, junction, tones.tolerance));
      out.push_back(std::move(path));
    }
  }
  return out;
}

std::vector<InkStroke> face_strokes(const std::vector<sim::FaceStroke>& runs, const Rgb& color) {
  std::vector<InkStroke> out;
  for (const sim::FaceStroke& run : runs) {
    InkStroke s;
    s.kind = feature_name(run.feature);
    s.color = color;
    for (std::size_t i = 0; i < run.points.size(); ++i)
      if (s.points.empty() || (run.points[i] - s.points.back()).norm() > 1e-6) {
        s.points.push_back(run.points[i]);
        s.width.push_back(run.width[i]);
      }
    if (s.points.size() < 2) continue;
    // One cubic per span, so sample k sits at s = k / spans.
    s.curve = vector::catmull_rom_path(s.points);
    const int spans = s.curve.piece_count();
    for (std::size_t k = 0; k < s.points.size(); ++k)
      s.curve_width.emplace_back(double(k) / spans, s.width[k]);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace wisp::render
