// arrange_segments: the exact planar arrangement of the outline segments, written for them instead
// of CGAL's general sweep (which spent 3-5 microseconds an event allocating its lazy exact
// kernel's DAG). The segments' ends are snapped to a power-of-two grid fine enough that nothing
// visible moves (2^-k of the largest coordinate's power of two, k chosen so that every snapped
// coordinate is an integer of at most 29 bits: 1/2^17 px at 1024 px), and then every decision is
// an exact integer predicate, with no construction ever rounded:
//  - whether two segments meet: orientations, products of 30-bit differences (61 bits, int64);
//  - where along a segment: a crossing's parameter is a ratio of two 61-bit cross products, a
//    touching end's a ratio of two dot products; two parameters on one segment compare by
//    cross-multiplying (123 bits, int128). Equal parameters on a segment are the same point, and
//    that is the only way two crossings become one vertex: three segments through a point pair up
//    on each of them, so the union of "equal on some segment" is exactly "the same point";
//  - the order of edges around a vertex: the directions of their segments, integer vectors;
//  - which boundary is a component's outside: the cycle through the gap facing -x at the
//    component's lexicographically smallest point, which is always a segment's end (an integer
//    point), never a crossing;
//  - the face a component lies in: a ray from that point towards -x; the nearest segment it meets
//    is a comparison of ratios of 61- and 30-bit integers.
// Candidate pairs come from a uniform grid (each segment registered in the cells its conservative
// extent per column reaches). The output is PlanarMap, the same plain DCEL CGAL's arrangement was
// copied into, in an order that depends only on the input. arrangement_cgal.cpp keeps the CGAL
// version as the reference the tests compare against.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "vector/buckets.hpp"
#include "vector/planar_map.hpp"
#include "vector/size_hint.hpp"

namespace wisp::vector {

namespace {

using Int = std::int64_t;
__extension__ typedef __int128 Int128;

struct IPoint {
  Int x = 0, y = 0;
};
bool operator==(IPoint a, IPoint b) {
  return a.x == b.x && a.y == b.y;
}
bool lex_less(IPoint a, IPoint b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}
Int cross(IPoint a, IPoint b) {
  return a.x * b.y - a.y * b.x;
}
Int dot(IPoint a, IPoint b) {
  return a.x * b.x + a.y * b.y;
}
IPoint operator-(IPoint a, IPoint b) {
  return {a.x - b.x, a.y - b.y};
}
IPoint operator-(IPoint a) {
  return {-a.x, -a.y};
}
Int orient(IPoint a, IPoint b, IPoint c) {
  return cross(b - a, c - a);
}

// Counter-clockwise from +x: the directions of [0, pi) first, then [pi, 2 pi).
bool angle_less(IPoint a, IPoint b) {
  const bool lower_a = a.y < 0 || (a.y == 0 && a.x < 0);
  const bool lower_b = b.y < 0 || (b.y == 0 && b.x < 0);
  if (lower_a != lower_b) return lower_b;
  return cross(a, b) > 0;
}

struct Segment {
  IPoint a, b;
  int input = -1;         // index into the input
  bool overlaps = false;  // shares a piece of positive length with a collinear segment
  IPoint dir() const { return b - a; }
};

// A point on a segment at parameter num / den (den > 0), and which point id it is.
struct Split {
  int segment;
  Int num, den;
  int point;
};
bool t_less(const Split& p, const Split& q) {
  return Int128(p.num) * q.den < Int128(q.num) * p.den;
}
bool t_equal(const Split& p, const Split& q) {
  return Int128(p.num) * q.den == Int128(q.num) * p.den;
}

// Union-find; the smaller index stays the root (so a class of points with a segment end in it is
// represented by the end: ends are numbered before crossings).
struct UnionFind {
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::vector<int> parent;
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int i, int j) {
    i = find(i), j = find(j);
    if (i != j) parent[std::max(i, j)] = std::min(i, j);
  }
};

// The candidate-pair grid over the snapped segments: cell lists in one array.
struct Grid {
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 1, ny = 1;
  std::vector<int> begin;  // cell c's segments: items[begin[c] .. begin[c+1])
  std::vector<int> items;

  int column(double x) const { return std::clamp(int(std::floor((x - x0) / cell)), 0, nx - 1); }
  int row(double y) const { return std::clamp(int(std::floor((y - y0) / cell)), 0, ny - 1); }

  // Calls fn(cell) for every cell the segment may pass through: per column, the segment's y range
  // over the column's x range, both widened by one grid unit against rounding (a steep segment's
  // y moves by its slope times an x rounding error: the x range is widened, not only y).
  template <class F>
  void for_each_cell(const Segment& s, F&& fn) const {
    const double ax = double(s.a.x), ay = double(s.a.y), bx = double(s.b.x), by = double(s.b.y);
    const double lo_x = std::min(ax, bx), hi_x = std::max(ax, bx);
    const int c0 = column(lo_x), c1 = column(hi_x);
    for (int c = c0; c <= c1; ++c) {
      double ylo, yhi;
      if (ax == bx || c0 == c1) {
        ylo = std::min(ay, by), yhi = std::max(ay, by);
      } else {
        const double xa = std::max(lo_x, x0 + c * cell - 1);
        const double xb = std::min(hi_x, x0 + (c + 1) * cell + 1);
        const double ya = ay + (xa - ax) * (by - ay) / (bx - ax);
        const double yb = ay + (xb - ax) * (by - ay) / (bx - ax);
        ylo = std::min(ya, yb), yhi = std::max(ya, yb);
      }
      const int r0 = row(ylo - 1), r1 = row(yhi + 1);
      for (int r = r0; r <= r1; ++r) fn(r * nx + c);
    }
  }
};

Grid build_grid(const std::vector<Segment>& segs) {
  Grid g;
  Int xmin = segs[0].a.x, xmax = xmin, ymin = segs[0].a.y, ymax = ymin;
  for (const Segment& s : segs)
    for (IPoint p : {s.a, s.b}) {
      xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
      ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
    }
  const double w = double(xmax - xmin), h = double(ymax - ymin);
  // About one cell per segment, at most 2048 a side.
  g.cell = std::max({std::sqrt(w * h / double(segs.size())), std::max(w, h) / 2048, 1.0});
  g.x0 = double(xmin), g.y0 = double(ymin);
  g.nx = int(w / g.cell) + 1, g.ny = int(h / g.cell) + 1;
  Buckets<int> cells = bucket<int>(g.nx * g.ny, [&](const auto& put) {
    for (int i = 0; i < int(segs.size()); ++i) g.for_each_cell(segs[i], [&](int c) { put(c, i); });
  });
  g.begin = std::move(cells.begin), g.items = std::move(cells.items);
  return g;
}

// Splits the segments at every point where they meet: ends lying inside another segment, crossings,
// and the ends of collinear overlaps. Appends to `splits`; crossings get new point ids from
// `next_point` on, and `crossing_at` says where each lies (segment, parameter) for its coordinates.
struct Intersector {
  std::vector<Segment>& segs;
  const std::vector<int>& end_id;  // per segment 2 i (a) and 2 i + 1 (b)
  std::vector<Split>& splits;
  std::vector<Split>& crossing_at;
  int next_point;

  // p strictly inside segment s (known to lie on its line): a split of s at p.
  void touch(int s, IPoint p, int id) {
    const Segment& seg = segs[s];
    const IPoint d = seg.dir();
    const Int num = dot(p - seg.a, d), den = dot(d, d);
    if (num > 0 && num < den) splits.push_back({s, num, den, id});
  }

  void test(int i, int j) {
    Segment& p = segs[i];
    Segment& q = segs[j];
    const Int o1 = orient(p.a, p.b, q.a), o2 = orient(p.a, p.b, q.b);
    if ((o1 > 0 && o2 > 0) || (o1 < 0 && o2 < 0)) return;
    const Int o3 = orient(q.a, q.b, p.a), o4 = orient(q.a, q.b, p.b);
    if ((o3 > 0 && o4 > 0) || (o3 < 0 && o4 < 0)) return;
    if (o1 == 0 && o2 == 0) {  // collinear: each splits the other at its ends inside it
      const IPoint d = p.dir();
      const Int qa = dot(q.a - p.a, d), qb = dot(q.b - p.a, d), len = dot(d, d);
      if (std::max(qa, qb) <= 0 || std::min(qa, qb) >= len) return;  // at most an end shared
      p.overlaps = q.overlaps = true;
      touch(i, q.a, end_id[2 * j]);
      touch(i, q.b, end_id[2 * j + 1]);
      touch(j, p.a, end_id[2 * i]);
      touch(j, p.b, end_id[2 * i + 1]);
      return;
    }
    if (o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) {  // a proper crossing inside both
      const IPoint r = p.dir(), s = q.dir();
      Int den = cross(r, s), tp = cross(q.a - p.a, s), tq = cross(q.a - p.a, r);
      if (den < 0) den = -den, tp = -tp, tq = -tq;
      const int id = next_point++;
      splits.push_back({i, tp, den, id});
      splits.push_back({j, tq, den, id});
      crossing_at.push_back({i, tp, den, id});
      return;
    }
    // An end of one lies on the other (inside it, or at its end: touch() keeps only the inside).
    if (o1 == 0) touch(i, q.a, end_id[2 * j]);
    if (o2 == 0) touch(i, q.b, end_id[2 * j + 1]);
    if (o3 == 0) touch(j, p.a, end_id[2 * i]);
    if (o4 == 0) touch(j, p.b, end_id[2 * i + 1]);
  }
};

}  // namespace

PlanarMap arrange_segments(const std::vector<OutlineSegment>& input) {
  PlanarMap map;
  // Snap: the largest power of two at which every coordinate rounds to at most 2^29.
  double largest = 0;
  for (int i = 0; i < int(input.size()); ++i) {
    const OutlineSegment& s = input[i];
    if (!s.a.allFinite() || !s.b.allFinite())
      throw std::invalid_argument("arrangement: segment " + std::to_string(i) + " is not finite");
    largest = std::max({largest, s.a.cwiseAbs().maxCoeff(), s.b.cwiseAbs().maxCoeff()});
  }
  int exponent = 0;
  if (largest > 0) std::frexp(largest, &exponent);  // largest < 2^exponent
  const int shift = 29 - exponent;
  auto snap = [&](const Eigen::Vector2d& p) {
    return IPoint{Int(std::llround(std::ldexp(p.x(), shift))),
                  Int(std::llround(std::ldexp(p.y(), shift)))};
  };
  std::vector<Segment> segs;
  segs.reserve(input.size());
  for (int i = 0; i < int(input.size()); ++i) {
    Segment s{snap(input[i].a), snap(input[i].b), i};
    if (!(s.a == s.b)) segs.push_back(s);
  }
  if (segs.empty()) {
    map.faces.resize(1);
    map.unbounded_face = 0;
    map.source_begin = {0};
    return map;
  }
  const int n = int(segs.size());

  // Point ids of the ends: equal points one id, numbered in xy order.
  std::vector<int> end_id(2 * n);
  std::vector<IPoint> end_point;           // per end id
  std::vector<Eigen::Vector2d> end_input;  // per end id: the first input point snapped to it
  {
    // An outline's consecutive segments share their meeting point: each such end is sorted once.
    struct End {
      IPoint p;
      int e;
    };
    std::vector<End> ends;
    ends.reserve(size_t(n) + 16);
    for (int i = 0; i < n; ++i) {
      if (i == 0 || !(segs[i].a == segs[i - 1].b)) ends.push_back({segs[i].a, 2 * i});
      ends.push_back({segs[i].b, 2 * i + 1});
    }
    std::sort(ends.begin(), ends.end(), [](const End& u, const End& v) {
      return lex_less(u.p, v.p) || (u.p == v.p && u.e < v.e);
    });
    for (const End& end : ends) {
      if (end_point.empty() || !(end_point.back() == end.p)) {
        end_point.push_back(end.p);
        const OutlineSegment& s = input[segs[end.e / 2].input];
        end_input.push_back(end.e % 2 ? s.b : s.a);
      }
      end_id[end.e] = int(end_point.size()) - 1;
    }
    for (int i = 1; i < n; ++i)
      if (segs[i].a == segs[i - 1].b) end_id[2 * i] = end_id[2 * i - 1];
  }
  const int n_ends = int(end_point.size());

  // Every point where segments meet, as splits of the segments.
  std::vector<Split> splits;
  thread_local SizeHint splits_size, crossings_size;
  splits_size.reserve(splits, 4 * size_t(n));
  for (int i = 0; i < n; ++i) {
    splits.push_back({i, 0, 1, end_id[2 * i]});
    splits.push_back({i, 1, 1, end_id[2 * i + 1]});
  }
  std::vector<Split> crossing_at;  // per crossing id (from n_ends on)
  crossings_size.reserve(crossing_at);
  const Grid grid = build_grid(segs);
  {
    Intersector meet{segs, end_id, splits, crossing_at, n_ends};
    std::vector<int> tested(n, -1);  // the last i tested against j: each pair once
    for (int i = 0; i < n; ++i)
      grid.for_each_cell(segs[i], [&](int c) {
        for (int k = grid.begin[c]; k < grid.begin[c + 1]; ++k) {
          const int j = grid.items[k];
          if (j <= i || tested[j] == i) continue;
          tested[j] = i;
          meet.test(i, j);
        }
      });
  }
  splits_size.remember(splits);
  crossings_size.remember(crossing_at);
  const int n_points = n_ends + int(crossing_at.size());

  // Splits grouped by segment (stable, so in the order found), then by parameter; equal
  // parameters on a segment are one point.
  Buckets<Split> by_segment = bucket<Split>(n, [&](const auto& put) {
    for (const Split& s : splits) put(s.segment, s);
  });
  const std::vector<int> split_begin = std::move(by_segment.begin);
  splits = std::move(by_segment.items);
  UnionFind classes(n_points);
  for (int i = 0; i < n; ++i) {
    const auto first = splits.begin() + split_begin[i], last = splits.begin() + split_begin[i + 1];
    std::sort(first, last, [](const Split& p, const Split& q) {
      return t_less(p, q) || (!t_less(q, p) && p.point < q.point);
    });
    for (auto s = first + 1; s < last; ++s)
      if (t_equal(*(s - 1), *s)) classes.unite((s - 1)->point, s->point);
  }
  // Vertices: the classes' roots, ends first (in xy order), then crossings as found.
  std::vector<int> vertex_of(n_points, -1);
  int n_vertices = 0;
  for (int p = 0; p < n_points; ++p)
    if (classes.find(p) == p) vertex_of[p] = n_vertices++;
  for (int p = 0; p < n_points; ++p) vertex_of[p] = vertex_of[classes.find(p)];
  const int n_end_vertices = n_ends;  // every end is its class's root: vertices 0 .. n_ends - 1

  // Edges: the pieces between consecutive distinct points of each segment. Pieces of
  // overlapping segments are the same straight edge when their end vertices are.
  struct EdgeSource {
    int edge, input;
    bool along;
  };
  std::vector<int> edge_from, edge_to, edge_segment;  // halfedge 2e runs from -> to along segment
  std::vector<EdgeSource> edge_sources;
  std::vector<int> piece_edge(splits.size(), -1);  // per split: the edge of the piece after it
  std::unordered_map<std::uint64_t, int> shared;
  for (int i = 0; i < n; ++i) {
    int run = split_begin[i];  // first split of the current point
    for (int k = split_begin[i] + 1; k < split_begin[i + 1]; ++k) {
      const int u = vertex_of[splits[run].point], v = vertex_of[splits[k].point];
      if (u == v) continue;
      int e = int(edge_from.size());
      if (segs[i].overlaps) {
        const std::uint64_t key =
            std::uint64_t(std::min(u, v)) << 32 | std::uint64_t(std::max(u, v));
        const auto [it, added] = shared.emplace(key, e);
        e = it->second;
        if (!added) {
          edge_sources.push_back({e, segs[i].input, edge_from[e] == u});
          for (int r = run; r < k; ++r) piece_edge[r] = e;
          run = k;
          continue;
        }
      }
      edge_from.push_back(u), edge_to.push_back(v), edge_segment.push_back(i);
      edge_sources.push_back({e, segs[i].input, true});
      for (int r = run; r < k; ++r) piece_edge[r] = e;
      run = k;
    }
  }
  const int n_edges = int(edge_from.size());
  std::vector<IPoint> edge_dir(n_edges);  // of halfedge 2e: its first source's direction
  for (int e = 0; e < n_edges; ++e) edge_dir[e] = segs[edge_segment[e]].dir();
  auto direction = [&](int h) { return h % 2 ? -edge_dir[h / 2] : edge_dir[h / 2]; };
  auto target = [&](int h) { return h % 2 ? edge_from[h / 2] : edge_to[h / 2]; };

  // Around each vertex, its outgoing halfedges counter-clockwise; a halfedge's next is the
  // outgoing one clockwise after its twin (the face on its left continues there).
  Buckets<int> outgoing = bucket<int>(n_vertices, [&](const auto& put) {
    for (int h = 0; h < 2 * n_edges; ++h) put(target(h ^ 1), h);
  });
  const std::vector<int>& out_begin = outgoing.begin;
  std::vector<int>& out = outgoing.items;
  std::vector<int> out_pos(2 * n_edges);
  for (int v = 0; v < n_vertices; ++v) {
    if (out_begin[v + 1] - out_begin[v] > 2)  // two are in order either way round
      std::sort(out.begin() + out_begin[v], out.begin() + out_begin[v + 1],
                [&](int g, int h) { return angle_less(direction(g), direction(h)); });
    for (int k = out_begin[v]; k < out_begin[v + 1]; ++k) out_pos[out[k]] = k;
  }
  map.halfedges.resize(2 * size_t(n_edges));
  for (int h = 0; h < 2 * n_edges; ++h) {
    const int v = target(h), k = out_pos[h ^ 1];
    map.halfedges[h].target = v;
    map.halfedges[h].next = out[k == out_begin[v] ? out_begin[v + 1] - 1 : k - 1];
  }

  // Cycles of `next`, and the connected components of the vertices.
  std::vector<int> cycle(2 * n_edges, -1), cycle_first;
  for (int h0 = 0; h0 < 2 * n_edges; ++h0) {
    if (cycle[h0] >= 0) continue;
    const int c = int(cycle_first.size());
    cycle_first.push_back(h0);
    for (int h = h0; cycle[h] < 0; h = map.halfedges[h].next) cycle[h] = c;
  }
  UnionFind components(n_vertices);
  for (int e = 0; e < n_edges; ++e) components.unite(edge_from[e], edge_to[e]);
  // A component's xy-smallest point is a segment's end (every segment's smallest point is), so
  // its lowest vertex among the ends; the cycle leaving it most counter-clockwise bounds the
  // component from outside (the gap towards -x is on its left).
  std::vector<int> lowest(n_vertices, -1);  // per component root
  std::vector<IPoint> vertex_point(n_end_vertices);
  for (int p = 0; p < n_ends; ++p) vertex_point[vertex_of[p]] = end_point[p];
  for (int v = 0; v < n_end_vertices; ++v) {
    int& l = lowest[components.find(v)];
    if (l < 0 || lex_less(vertex_point[v], vertex_point[l])) l = v;
  }
  // Per cycle: the component it bounds from outside, or -1.
  std::vector<int> outside_of(cycle_first.size(), -1);
  std::vector<int> component_roots;
  for (int v = 0; v < n_vertices; ++v) {
    if (lowest[v] < 0) continue;
    const int w = lowest[v];
    int best = out[out_begin[w]];
    for (int k = out_begin[w] + 1; k < out_begin[w + 1]; ++k)
      if (cross(direction(best), direction(out[k])) > 0) best = out[k];
    outside_of[cycle[best]] = int(component_roots.size());
    component_roots.push_back(v);
  }

  // Faces: the unbounded one, then one per cycle that is not a component's outside.
  std::vector<int> face_of_cycle(cycle_first.size(), -1);
  map.unbounded_face = 0;
  map.faces.resize(1);
  for (int c = 0; c < int(cycle_first.size()); ++c)
    if (outside_of[c] < 0) {
      face_of_cycle[c] = int(map.faces.size());
      map.faces.push_back({cycle_first[c], 0, 0});
    }

  // The face each component lies in: shoot a ray from its lowest point towards -x; the nearest
  // segment met, at an inner point of one of its edges or at a vertex, has the face on its side.
  // `around` is the halfedge whose left face holds the component, -1 for the unbounded face.
  const int n_components = int(component_roots.size());
  std::vector<int> around(n_components, -1);
  std::vector<int> seen(n, -1);
  for (int m = 0; m < n_components; ++m) {
    const IPoint o = vertex_point[lowest[component_roots[m]]];
    // Best hit so far: x = num / den (den > 0) on segment `hit`, or at vertex `hit_vertex`.
    Int best_num = 0, best_den = 0;
    int hit = -1, hit_vertex = -1;
    Split hit_t{};
    const int r = grid.row(double(o.y));
    for (int c = std::min(grid.column(double(o.x)) + 1, grid.nx - 1); c >= 0; --c) {
      const int cell = r * grid.nx + c;
      for (int k = grid.begin[cell]; k < grid.begin[cell + 1]; ++k) {
        const int i = grid.items[k];
        if (seen[i] == m) continue;
        seen[i] = m;
        IPoint a = segs[i].a, b = segs[i].b;
        if (a.y > b.y) std::swap(a, b);
        if (o.y < a.y || o.y > b.y) continue;
        Int num, den = 1;
        int vertex = -1;
        Split t{i, 0, 1, -1};
        if (a.y == b.y) {  // along the ray: met at its end nearer o
          const bool a_right = a.x > b.x;
          num = a_right ? a.x : b.x;
          const Segment& s = segs[i];
          vertex = vertex_of[end_id[2 * i + ((a_right ? a : b) == s.b ? 1 : 0)]];
        } else if (o.y == a.y || o.y == b.y) {
          const IPoint e = o.y == a.y ? a : b;
          num = e.x;
          vertex = vertex_of[end_id[2 * i + (e == segs[i].b ? 1 : 0)]];
        } else {
          den = b.y - a.y;
          num = a.x * den + (o.y - a.y) * (b.x - a.x);
          // The parameter along the segment as stored (from s.a to s.b).
          const Segment& s = segs[i];
          t.num = s.a.y < s.b.y ? o.y - s.a.y : s.a.y - o.y;
          t.den = den;
        }
        if (Int128(num) >= Int128(o.x) * den) continue;  // not left of o
        if (hit >= 0 && Int128(num) * best_den <= Int128(best_num) * den) continue;
        best_num = num, best_den = den, hit = i, hit_vertex = vertex, hit_t = t;
      }
      // Segments met only in columns further left lie at x < this column's left side.
      if (hit >= 0 && double(best_num) / double(best_den) > grid.x0 + c * grid.cell + 2) break;
    }
    if (hit < 0) continue;  // in the unbounded face
    if (hit_vertex < 0) {
      // Inside the segment: at one of its points (a vertex), or inside one of its edges.
      const auto first = splits.begin() + split_begin[hit],
                 last = splits.begin() + split_begin[hit + 1];
      const auto after = std::upper_bound(first, last, hit_t, t_less);  // first > t
      const auto at = after - 1;                                        // last <= t
      if (t_equal(*at, hit_t)) {
        hit_vertex = vertex_of[at->point];
      } else {
        const int e = piece_edge[at - splits.begin()];
        around[m] = direction(2 * e).y < 0 ? 2 * e : 2 * e + 1;  // the side facing +x is left of
                                                                 // the halfedge going down
        continue;
      }
    }
    // At a vertex: the sector around it that holds +x (no edge leaves it that way: that edge
    // would be nearer o) lies between its last and its first outgoing halfedge.
    int last = out[out_begin[hit_vertex]];  // (two outgoing halfedges are not sorted)
    for (int k = out_begin[hit_vertex] + 1; k < out_begin[hit_vertex + 1]; ++k)
      if (angle_less(direction(last), direction(out[k]))) last = out[k];
    around[m] = last;
  }
  // A component inside a face bounded by another component's outside lies in that one's face.
  std::vector<int> face_of_component(n_components, -2);
  auto face_of = [&](int m) {
    std::vector<int> chain;
    while (face_of_component[m] == -2) {
      if (int(chain.size()) > n_components)
        throw std::logic_error("arrangement: components nested in a cycle");
      chain.push_back(m);
      const int h = around[m];
      if (h < 0) {
        face_of_component[m] = 0;
        break;
      }
      const int c = cycle[h];
      if (outside_of[c] < 0) {
        face_of_component[m] = face_of_cycle[c];
        break;
      }
      m = outside_of[c];
    }
    for (int k : chain) face_of_component[k] = face_of_component[m];
    return face_of_component[m];
  };
  for (int c = 0; c < int(cycle_first.size()); ++c)
    if (outside_of[c] >= 0) face_of_cycle[c] = face_of(outside_of[c]);
  for (int h = 0; h < 2 * n_edges; ++h) map.halfedges[h].face = face_of_cycle[cycle[h]];
  // Holes, grouped by face in component order.
  {
    std::vector<int> outside_cycle(n_components);
    for (int c = 0; c < int(cycle_first.size()); ++c)
      if (outside_of[c] >= 0) outside_cycle[outside_of[c]] = c;
    Buckets<int> holes = bucket<int>(int(map.faces.size()), [&](const auto& put) {
      for (int m = 0; m < n_components; ++m) put(face_of(m), cycle_first[outside_cycle[m]]);
    });
    for (size_t f = 0; f < map.faces.size(); ++f)
      map.faces[f].holes_begin = holes.begin[f], map.faces[f].holes_end = holes.begin[f + 1];
    map.holes = std::move(holes.items);
  }

  // Sources per edge, in input order (they were found segment by segment).
  Buckets<PlanarMap::Source> sources = bucket<PlanarMap::Source>(n_edges, [&](const auto& put) {
    for (const EdgeSource& s : edge_sources) put(s.edge, {s.input, s.along});
  });
  map.source_begin = std::move(sources.begin), map.sources = std::move(sources.items);

  // Coordinates: a segment's end as given (so that the resolver's parameters along a segment
  // are its own at its ends, and consecutive pieces abut exactly), a crossing rounded once from
  // its exact coordinates on the snapped grid.
  map.vertices.resize(n_vertices);
  for (int p = 0; p < n_ends; ++p) map.vertices[vertex_of[p]] = end_input[p];
  for (const Split& x : crossing_at) {
    if (classes.find(x.point) != x.point) continue;
    const Segment& s = segs[x.segment];
    const IPoint d = s.dir();
    const Int128 nx = Int128(s.a.x) * x.den + Int128(d.x) * x.num;
    const Int128 ny = Int128(s.a.y) * x.den + Int128(d.y) * x.num;
    const long double den = (long double)x.den;
    map.vertices[vertex_of[x.point]] = {double(std::ldexp((long double)nx / den, -shift)),
                                        double(std::ldexp((long double)ny / den, -shift))};
  }
  return map;
}

}  // namespace wisp::vector
