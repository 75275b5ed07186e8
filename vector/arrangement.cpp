// build_arrangement: flattens the wisps into outline segments, leaves out the provably hidden
// wisps, adds the depth seams, arranges them all (segment_arrangement.cpp), then decides on the
// plain planar map: winding numbers per face, the front-most wisp per face, visibility per outline
// piece, the hair mask and the ink polylines.
#include "vector/arrangement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "diffusion/timer.hpp"
#include "vector/band_depth.hpp"
#include "vector/buckets.hpp"
#include "vector/depth_seams.hpp"
#include "vector/hidden_wisps.hpp"
#include "vector/ink.hpp"
#include "vector/planar_map.hpp"
#include "vector/size_hint.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

using diffusion::Clock;
using diffusion::ms_since;

constexpr int kSeamId = -2;  // the id of depth seams' segments (the view frame's is -1)

using Winding = std::pair<int, int>;  // (wisp, winding != 0)
using Cover = std::vector<Winding>;   // sorted by wisp

// A face's cover as stored: a range of Resolver::cover_pool.
struct CoverRange {
  const Winding *first, *last;
  const Winding* begin() const { return first; }
  const Winding* end() const { return last; }
  bool empty() const { return first == last; }
};

int winding(CoverRange c, int wisp) {
  const Winding* it = std::lower_bound(c.first, c.last, std::make_pair(wisp, INT32_MIN));
  return it != c.last && it->first == wisp ? it->second : 0;
}

// Adds delta to the winding of `wisp` in the cover c[from ..] (the end of c), keeping it sorted and
// without zeros.
void add_winding(Cover& c, size_t from, int wisp, int delta) {
  const auto it = std::lower_bound(c.begin() + from, c.end(), std::make_pair(wisp, INT32_MIN));
  if (it != c.end() && it->first == wisp) {
    it->second += delta;
    if (it->second == 0) c.erase(it);
  } else {
    c.insert(it, {wisp, delta});
  }
}

// Appends the outline of wisp w's band between sections first and last: the whole outline
// from 0 to n, else a piece of it whose caps inside the band are cuts (OutlineSegment::cut).
void append_outline(const Wisp& wisp, int w, int first, int last,
                    std::vector<OutlineSegment>& out) {
  const int n = int(wisp.sections.size()) - 1;
  const std::vector<OutlineVertex> poly = outline_polygon(wisp, first, last);
  for (size_t i = 0; i < poly.size(); ++i) {
    const OutlineVertex &a = poly[i], &b = poly[(i + 1) % poly.size()];
    OutlineSegment seg{a.p, b.p, w, a.side, a.s, i + 1 < poly.size() ? b.s : 1.0, a.depth, b.depth};
    seg.cut = (a.side == Side::Root && first > 0) || (a.side == Side::Tip && last < n);
    if (seg.cut) seg.s1 = seg.s0;
    out.push_back(seg);
  }
}

// Replaces the outline of every kept wisp with hidden cells by the outlines of its runs of
// visible cells: the hidden cells' sides no longer enter the sweep. Something nearer covers every
// point of a hidden cell (vector/hidden_wisps.hpp), so leaving the cell out of its wisp's cover
// changes no face's front, and a cut (the section line between a hidden and a kept cell) has the
// same front on both sides: no visible piece, no ink.
void cut_hidden_cells(const std::vector<Wisp>& wisps, const HiddenParts& hidden,
                      std::vector<OutlineSegment>& segments) {
  const int n = int(wisps.size());
  std::vector<char> cut(n, 0);
  for (int w = 0; w < n; ++w)
    cut[w] = !hidden.wisps[w] &&
             std::find(hidden.cells[w].begin(), hidden.cells[w].end(), 1) != hidden.cells[w].end();
  segments.erase(std::remove_if(segments.begin(), segments.end(),
                                [&](const OutlineSegment& s) {
                                  return s.wisp >= 0 && s.wisp < n && cut[s.wisp];
                                }),
                 segments.end());
  for (int w = 0; w < n; ++w) {
    if (!cut[w]) continue;
    const std::vector<char>& cells = hidden.cells[w];
    for (int k = 0; k < int(cells.size());) {
      const int first = k;
      while (k < int(cells.size()) && !cells[k]) ++k;
      if (k > first) append_outline(wisps[w], w, first, k, segments);
      while (k < int(cells.size()) && cells[k]) ++k;
    }
  }
}

void check_wisp(const Wisp& w, int index) {
  const std::string name = "wisp " + std::to_string(index);
  if (w.sections.size() < 2) throw std::invalid_argument(name + ": needs at least 2 sections");
  for (const Section& s : w.sections)
    if (!s.left.allFinite() || !s.right.allFinite() || !s.centre.allFinite() ||
        !std::isfinite(s.depth))
      throw std::invalid_argument(name + ": section is not finite");
}

// Everything decided on the planar map.
struct Resolver {
  const std::vector<Wisp>& wisps;
  const std::vector<OutlineSegment>& segments;
  const PlanarMap& map;
  const ArrangementOptions& options;

  Resolver(const std::vector<Wisp>& w, const std::vector<OutlineSegment>& s, const PlanarMap& m,
           const ArrangementOptions& o)
      : wisps(w), segments(s), map(m), options(o) {
    cells.reserve(w.size());
    nearest.reserve(w.size());
    for (const Wisp& wisp : w) {
      cells.push_back(band_cells(wisp));
      // A band depth interpolates two sections' depths: within rounding of the nearest one.
      double lo = INFINITY, size = 0;
      for (const Section& sec : wisp.sections)
        lo = std::min(lo, sec.depth), size = std::max(size, std::abs(sec.depth));
      nearest.push_back(lo - 1e-12 * size);
    }
    source_wisp.resize(m.sources.size());
    for (size_t i = 0; i < m.sources.size(); ++i) source_wisp[i] = s[m.sources[i].segment].wisp;
  }

  std::vector<BandCells> cells;  // per wisp, for depth lookups
  std::vector<double> nearest;   // per wisp: no band depth of it is below this
  // Per face its cover: cover_pool[cover_at[f].first .. cover_at[f].second), one allocation for
  // all faces instead of one each.
  std::vector<Winding> cover_pool;
  std::vector<std::pair<int, int>> cover_at;
  std::vector<int> pool_order;  // the faces in the order of their covers in cover_pool
  CoverRange cover(int f) const {
    return {cover_pool.data() + cover_at[f].first, cover_pool.data() + cover_at[f].second};
  }
  std::vector<Vector2d> sample;  // per face, for covered faces (all bounded ones with keep_faces)
  std::vector<char> hair;        // per face: covered and in view
  std::vector<char> in_view;
  std::vector<int> front;
  std::vector<double> front_depth;
  std::vector<char> visible;     // per entry of map.sources
  std::vector<int> source_wisp;  // per entry of map.sources: its segment's wisp (dense; a segment
                                 // is 80 bytes, and the sources reach them in no order)
  std::vector<std::pair<double, int>> scratch_order;  // of order_faces, kept across faces

  int n_wisps() const { return int(wisps.size()); }
  bool is_wisp(int id) const { return id >= 0 && id < n_wisps(); }
  // The hair base's segments carry this id; as a face's front it is n_wisps().
  int base_id() const { return n_wisps() + int(options.occluders.size()); }
  bool is_base_front(int f) const { return front[f] == n_wisps(); }

  template <class F>
  void for_each_ccb(int f, F&& fn) const {
    const PlanarMap::Face& face = map.faces[f];
    if (face.outer >= 0) fn(face.outer);
    for (int i = face.holes_begin; i < face.holes_end; ++i) fn(map.holes[i]);
  }

  std::vector<Vector2d> ring(int h0) const {
    std::vector<Vector2d> points;
    int h = h0;
    do {
      points.push_back(map.vertices[map.source(h)]);
      h = map.halfedges[h].next;
    } while (h != h0);
    return points;
  }

  // Winding numbers: zero in the unbounded face; crossing a segment from its left (CGAL's
  // orientation) to its right lowers its wisp's winding by one. Breadth-first over the faces,
  // each face's halfedges grouped in two linear passes (walking its cycles by `next` missed the
  // cache at nearly every step); a winding number does not depend on the path it is counted
  // along, so neither does the order.
  void propagate_cover() {
    const Buckets<int> by_face = bucket<int>(int(map.faces.size()), [&](const auto& put) {
      for (int h = 0; h < 2 * map.edge_count(); ++h) put(map.halfedges[h].face, h);
    });
    cover_pool.clear();
    thread_local SizeHint pool_size;
    pool_size.reserve(cover_pool);
    cover_at.assign(map.faces.size(), {0, 0});
    std::vector<char> seen(map.faces.size(), 0);
    std::vector<int>& queue = pool_order;
    queue.assign(1, map.unbounded_face);
    seen[map.unbounded_face] = 1;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      for (int k = by_face.begin[f]; k < by_face.begin[f + 1]; ++k) {
        const int h = by_face.items[k], g = map.halfedges[h ^ 1].face;
        if (seen[g]) continue;
        seen[g] = 1;
        // g's cover is f's, copied to the pool's end and changed there.
        const size_t start = cover_pool.size();
        const auto [from, to] = cover_at[f];
        cover_pool.resize(start + size_t(to - from));
        std::copy(cover_pool.begin() + from, cover_pool.begin() + to, cover_pool.begin() + start);
        const int e = h / 2;
        for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
          const PlanarMap::Source& s = map.sources[i];
          const int w = source_wisp[i];  // occluders count like wisps here
          if (w < 0) continue;
          const bool along_h = s.along == (h % 2 == 0);  // face f lies on the segment's left
          add_winding(cover_pool, start, w, along_h ? -1 : +1);
        }
        cover_at[g] = {int(start), int(cover_pool.size())};
        queue.push_back(g);
      }
    }
    for (int f = 0; f < int(map.faces.size()); ++f)
      if (!seen[f]) queue.push_back(f);  // not reached: an empty cover
    pool_size.remember(cover_pool);
  }

  // Per face, an interior point: the middle of the widest span cut from the face by one of three
  // horizontal lines (even-odd over all its boundaries, so holes are avoided). The y-ranges and
  // the lines' crossings are gathered in linear passes over the edges instead of walking each
  // face's cycles (a cache miss at nearly every step of the walk); each halfedge's crossing is
  // computed from its own source and target as before and the xs are sorted per line, so the
  // points do not depend on the order the crossings are found in. Also whether each is in view.
  void sample_faces(const std::vector<char>& wanted) {
    const int faces = int(map.faces.size()), edges = map.edge_count();
    constexpr double fracs[3] = {0.5, 0.25, 0.75};    // tried in this order: ties go to the first
    std::vector<double> lines(5 * size_t(faces), 0);  // per face: y0, y1, then the lines' y
    for (int f = 0; f < faces; ++f) lines[5 * f] = INFINITY, lines[5 * f + 1] = -INFINITY;
    for (int e = 0; e < edges; ++e) {
      const Vector2d &a = map.vertices[map.halfedges[2 * e + 1].target],
                     &b = map.vertices[map.halfedges[2 * e].target];
      for (const auto& [f, y] : {std::pair{map.halfedges[2 * e].face, a.y()},
                                 std::pair{map.halfedges[2 * e + 1].face, b.y()}}) {
        double* r = &lines[5 * size_t(f)];
        r[0] = std::min(r[0], y), r[1] = std::max(r[1], y);
      }
    }
    for (int f = 0; f < faces; ++f) {
      double* r = &lines[5 * size_t(f)];
      if (wanted[f])
        for (int k = 0; k < 3; ++k) r[2 + k] = r[0] + fracs[k] * (r[1] - r[0]);
    }
    // The crossings, found once, then grouped by (face, line).
    std::vector<std::pair<int, double>> found;
    thread_local SizeHint found_size;
    found_size.reserve(found);
    for (int h = 0; h < 2 * edges; ++h) {
      const int f = map.halfedges[h].face;
      if (!wanted[f]) continue;
      const Vector2d &a = map.vertices[map.halfedges[h ^ 1].target],
                     &b = map.vertices[map.halfedges[h].target];
      const double* r = &lines[5 * size_t(f)];
      for (int k = 0; k < 3; ++k) {
        const double y = r[2 + k];
        if ((a.y() > y) != (b.y() > y))
          found.emplace_back(3 * f + k, a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
      }
    }
    found_size.remember(found);
    Buckets<double> xs = bucket<double>(3 * faces, [&](const auto& put) {
      for (const auto& [key, x] : found) put(key, x);
    });
    for (int f = 0; f < faces; ++f) {
      if (!wanted[f]) continue;
      const PlanarMap::Face& face = map.faces[f];
      const int h0 = face.outer >= 0 ? face.outer : map.holes[face.holes_begin];
      Vector2d best = 0.5 * (map.vertices[map.source(h0)] + map.vertices[map.halfedges[h0].target]);
      double best_width = 0;
      for (int k = 0; k < 3; ++k) {
        double *first = xs.items.data() + xs.begin[3 * f + k],
               *last = xs.items.data() + xs.begin[3 * f + k + 1];
        std::sort(first, last);
        for (double* x = first; x + 1 < last; x += 2)
          if (x[1] - x[0] > best_width)
            best_width = x[1] - x[0], best = {0.5 * (x[0] + x[1]), lines[5 * size_t(f) + 2 + k]};
      }
      sample[f] = best;
      in_view[f] = !options.clip_to_view || options.view.contains(best);
    }
  }

  void order_faces() {
    const int faces = int(map.faces.size());
    sample.assign(faces, Vector2d::Zero());
    in_view.assign(faces, 0);
    hair.assign(faces, 0);
    front.assign(faces, -1);
    front_depth.assign(faces, 0);
    std::vector<char> wanted(faces, 0);
    for (int f = 0; f < faces; ++f)
      wanted[f] = f != map.unbounded_face && (!cover(f).empty() || options.keep_faces);
    sample_faces(wanted);
    for (int f : pool_order) {  // the covers in memory order: read from cache, not memory
      if (!wanted[f] || cover(f).empty()) continue;
      // Front-most by depth at the sample point; ties go to the lower wisp index. An occluder
      // in front of every wisp makes the face its own: not hair, unless the hair base covers
      // the face and is nearer than that occluder (it lies on the head, behind every wisp).
      // The candidates are tried in the order of their bounds (occluders first), until a bound
      // is beyond the front-most depth so far: the wisps wholly behind it need no lookup.
      // Usually two or three are tried, of covers of up to dozens: the first is found by one
      // pass, and only the candidates whose bound is within its depth are gathered and sorted.
      double best = INFINITY;
      const CoverRange candidates = cover(f);
      // The hair base's id is the largest: last in the cover, which is sorted by id.
      const bool on_base = (candidates.last - 1)->first == base_id();
      const Winding* const end = candidates.last - (on_base ? 1 : 0);
      const auto bound_of = [&](int w) { return w < n_wisps() ? nearest[w] : -INFINITY; };
      const auto try_candidate = [&](int w) {
        const double z = w < n_wisps() ? band_depth(wisps[w], cells[w], sample[f]).depth
                                       : options.occluders[w - n_wisps()].depth(sample[f]);
        if (z < best || (z == best && w < front[f])) best = z, front[f] = w;
      };
      if (candidates.first != end) {
        std::pair<double, int> first(INFINITY, std::numeric_limits<int>::max());
        for (const Winding* c = candidates.first; c != end; ++c)
          first = std::min(first, std::pair<double, int>(bound_of(c->first), c->first));
        try_candidate(first.second);
        std::vector<std::pair<double, int>>& rest = scratch_order;  // (bound, wisp)
        rest.clear();
        for (const Winding* c = candidates.first; c != end; ++c)
          if (const double bound = bound_of(c->first); c->first != first.second && bound <= best)
            rest.emplace_back(bound, c->first);
        std::sort(rest.begin(), rest.end());
        for (const auto& [bound, w] : rest) {
          if (bound > best) break;
          try_candidate(w);
        }
      }
      if (front[f] < 0 || front[f] >= n_wisps()) {
        front[f] = -1;
        const double zb = on_base ? options.base.depth(sample[f]) : INFINITY;
        if (!(zb < best)) continue;
        front[f] = n_wisps(), best = zb;
      }
      front_depth[f] = best;
      hair[f] = in_view[f];
    }
  }

  double s_at(const OutlineSegment& seg, const Vector2d& p) const {
    const Vector2d ab = seg.b - seg.a;
    const double l = std::clamp((p - seg.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return seg.s0 + l * (seg.s1 - seg.s0);
  }

  // A piece is visible where its wisp is front-most on one side and no other pass of the same
  // wisp (a curl over itself) covers it from nearer the eye.
  void decide_visibility() {
    visible.assign(map.sources.size(), 0);
    for (int e = 0; e < map.edge_count(); ++e) {
      const int fl = map.halfedges[2 * e].face, fr = map.halfedges[2 * e + 1].face;
      for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
        const OutlineSegment& seg = segments[map.sources[i].segment];
        int w = seg.wisp;
        if (w == base_id()) w = n_wisps();
        if (!is_wisp(w) && w != n_wisps()) continue;
        bool vis = (hair[fl] && front[fl] == w) || (hair[fr] && front[fr] == w);
        if (w == n_wisps()) {
          visible[i] = vis;
          continue;
        }
        if (vis && winding(cover(fl), w) != 0 && winding(cover(fr), w) != 0) {
          const Vector2d m =
              0.5 * (map.vertices[map.source(2 * e)] + map.vertices[map.halfedges[2 * e].target]);
          const Vector2d ab = seg.b - seg.a;
          const double l = std::clamp((m - seg.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
          const double z = seg.z0 + l * (seg.z1 - seg.z0);
          const auto other = band_depth_inside(wisps[w], cells[w], m, 1e-6);
          if (other && other->depth < z * (1 - 1e-12)) vis = false;
        }
        visible[i] = vis;
      }
    }
  }

  // Per wisp (or, for the hair base, per path): the visible parameter intervals of its outline.
  std::vector<std::vector<std::pair<double, double>>> visible_intervals(bool base) const {
    struct Piece {
      double lo, hi;
      bool visible;
    };
    std::vector<std::vector<Piece>> pieces(base ? options.base.rings.size() : wisps.size());
    for (int e = 0; e < map.edge_count(); ++e) {
      const Vector2d &a = map.vertices[map.source(2 * e)],
                     &b = map.vertices[map.halfedges[2 * e].target];
      for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
        const OutlineSegment& seg = segments[map.sources[i].segment];
        if (base ? seg.wisp != base_id() : !is_wisp(seg.wisp)) continue;
        const double sa = s_at(seg, a), sb = s_at(seg, b);
        pieces[base ? seg.ring : seg.wisp].push_back(
            {std::min(sa, sb), std::max(sa, sb), visible[i] != 0});
      }
    }
    std::vector<std::vector<std::pair<double, double>>> out(pieces.size());
    for (size_t w = 0; w < pieces.size(); ++w) {
      auto& p = pieces[w];
      std::sort(p.begin(), p.end(), [](const Piece& x, const Piece& y) {
        return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
      });
      for (const Piece& piece : p) {
        if (!piece.visible || piece.hi <= piece.lo) continue;
        if (!out[w].empty() && piece.lo <= out[w].back().second + 1e-9)
          out[w].back().second = std::max(out[w].back().second, piece.hi);
        else
          out[w].push_back({piece.lo, piece.hi});
      }
    }
    return out;
  }

  bool occluder_edge(int e) const {
    for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
      const int w = source_wisp[i];
      if (w >= n_wisps() && w < base_id()) return true;
    }
    return false;
  }

  // Only depth seams run along edge e: no outline, so no ink line.
  bool seam_edge(int e) const {
    for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i)
      if (source_wisp[i] != kSeamId) return false;
    return true;
  }

  bool frame_edge(int e) const {
    for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i)
      if (source_wisp[i] == -1) return true;
    return false;
  }

  // The wisp whose visible outline runs along edge e (lowest index if several), or -1.
  int visible_wisp(int e) const {
    int best = -1;
    for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
      const int w = source_wisp[i];
      if (visible[i] && is_wisp(w) && (best < 0 || w < best)) best = w;
    }
    return best;
  }

  // Whether every source wisp of edge e is one of edge g's (sources are few: no allocation).
  bool wisps_within(int e, int g) const {
    for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
      const int w = source_wisp[i];
      bool found = false;
      for (int j = map.source_begin[g]; j < map.source_begin[g + 1] && !found; ++j)
        found = source_wisp[j] == w;
      if (!found) return false;
    }
    return true;
  }
  bool same_wisps(int e, int g) const { return wisps_within(e, g) && wisps_within(g, e); }

  // Vertices where outlines cross or touch: not a joint of exactly two edges of the same
  // source wisps.
  std::vector<char> intersection_flags() const {
    const int n = int(map.vertices.size());
    std::vector<int> degree(n, 0), first_edge(n, -1);
    std::vector<char> flag(n, 0);
    for (int e = 0; e < map.edge_count(); ++e) {
      for (int v : {map.source(2 * e), map.halfedges[2 * e].target}) {
        ++degree[v];
        if (first_edge[v] < 0)
          first_edge[v] = e;
        else if (!same_wisps(e, first_edge[v]))
          flag[v] = 1;
      }
    }
    for (int v = 0; v < n; ++v) flag[v] |= degree[v] != 2;
    return flag;
  }

  // `crossing`: intersection_flags().
  ArrangementView view(const std::vector<char>& crossing) const {
    ArrangementView v;
    v.faces.resize(map.faces.size());
    for (int f = 0; f < int(map.faces.size()); ++f) {
      ViewFace& vf = v.faces[f];
      const PlanarMap::Face& face = map.faces[f];
      vf.unbounded = f == map.unbounded_face;
      if (face.outer >= 0) vf.outer = ring(face.outer);
      for (int i = face.holes_begin; i < face.holes_end; ++i)
        vf.holes.push_back(ring(map.holes[i]));
      for (const Winding& c : cover(f))
        if (is_wisp(c.first)) vf.cover.push_back(c);
      vf.base = hair[f] && is_base_front(f);
      vf.front = hair[f] && !vf.base ? front[f] : -1;
      vf.front_depth = front_depth[f];
      vf.sample = sample[f];
      vf.in_view = in_view[f];
    }
    v.vertices.resize(map.vertices.size());
    for (int i = 0; i < int(map.vertices.size()); ++i) v.vertices[i].p = map.vertices[i];
    v.edges.resize(map.edge_count());
    for (int e = 0; e < map.edge_count(); ++e) {
      ViewEdge& ve = v.edges[e];
      const int va = map.source(2 * e), vb = map.halfedges[2 * e].target;
      ve.a = map.vertices[va];
      ve.b = map.vertices[vb];
      ve.face_left = map.halfedges[2 * e].face;
      ve.face_right = map.halfedges[2 * e + 1].face;
      for (int i = map.source_begin[e]; i < map.source_begin[e + 1]; ++i) {
        const OutlineSegment& seg = segments[map.sources[i].segment];
        // Occluder k appears as source -2 - k, the hair base and depth seams as -1 with `base`
        // or `seam` set.
        const bool base = seg.wisp == base_id(), seam = seg.wisp == kSeamId;
        ViewEdgeSource s;
        s.wisp = is_wisp(seg.wisp)                ? seg.wisp
                 : seg.wisp >= n_wisps() && !base ? -2 - (seg.wisp - n_wisps())
                                                  : -1;
        s.side = seg.side;
        s.visible = visible[i] != 0;
        s.base = base;
        s.seam = seam;
        s.cut = seg.cut;
        if (is_wisp(seg.wisp) || base) s.s0 = s_at(seg, ve.a), s.s1 = s_at(seg, ve.b);
        ve.sources.push_back(s);
      }
      const bool hl = hair[ve.face_left], hr = hair[ve.face_right];
      ve.silhouette = hl != hr && !frame_edge(e);
      ve.occlusion = hl && hr && front[ve.face_left] != front[ve.face_right];
    }
    for (int i = 0; i < int(v.vertices.size()); ++i) v.vertices[i].intersection = crossing[i];
    for (int e = 0; e < map.edge_count(); ++e) {
      ++v.vertices[map.source(2 * e)].degree;
      ++v.vertices[map.halfedges[2 * e].target].degree;
    }
    return v;
  }
};

}  // namespace

Eigen::AlignedBox2d image_rect(int width, int height) {
  return Eigen::AlignedBox2d(Vector2d(0, 0), Vector2d(width, height));
}

WispArrangement build_arrangement(const std::vector<Wisp>& wisps,
                                  const ArrangementOptions& options) {
  if (options.clip_to_view) {
    const auto& v = options.view;
    if (!v.min().allFinite() || !v.max().allFinite() || !(v.sizes().array() > 0).all())
      throw std::invalid_argument("arrangement: view must be a finite, non-empty rectangle");
  }
  for (size_t i = 0; i < wisps.size(); ++i) check_wisp(wisps[i], int(i));

  WispArrangement out;
  const auto t0 = Clock::now();
  const double cpu0 = diffusion::thread_cpu_ms();
  std::vector<OutlineSegment> segments;
  thread_local SizeHint segments_size;
  segments_size.reserve(segments);
  for (int w = 0; w < int(wisps.size()); ++w) {
    if (options.clip_to_view && !options.view.intersects(wisps[w].bounds)) continue;
    ++out.stats.wisps;
    append_outline(wisps[w], w, 0, int(wisps[w].sections.size()) - 1, segments);
  }
  for (size_t k = 0; k < options.occluders.size(); ++k) {
    const Occluder& o = options.occluders[k];
    if (o.ring.size() < 3 || !o.depth)
      throw std::invalid_argument("arrangement: occluder " + std::to_string(k) +
                                  " needs a ring of 3 or more points and a depth function");
    for (size_t i = 0; i < o.ring.size(); ++i) {
      if (!o.ring[i].allFinite())
        throw std::invalid_argument("arrangement: occluder " + std::to_string(k) + ": point " +
                                    std::to_string(i) + " is not finite");
      segments.push_back({o.ring[i], o.ring[(i + 1) % o.ring.size()], int(wisps.size() + k)});
    }
  }
  const HairBase& base = options.base;
  if (!base.empty() && !base.depth)
    throw std::invalid_argument("arrangement: the hair base needs a depth function");
  if (base.rings.size() != base.ring_s.size())
    throw std::invalid_argument("arrangement: the hair base needs a parameter per ring vertex");
  const int base_id = int(wisps.size() + options.occluders.size());
  for (int r = 0; r < int(base.rings.size()); ++r) {
    const auto& ring = base.rings[r];
    const auto& s = base.ring_s[r];
    if (ring.size() != s.size())
      throw std::invalid_argument("arrangement: hair base ring " + std::to_string(r) +
                                  ": one parameter per vertex expected");
    for (size_t i = 0; i < ring.size(); ++i) {
      if (!ring[i].allFinite())
        throw std::invalid_argument("arrangement: hair base ring " + std::to_string(r) +
                                    ": point " + std::to_string(i) + " is not finite");
      OutlineSegment seg{ring[i], ring[(i + 1) % ring.size()],         base_id, Side::Left,
                         s[i],    i + 1 < ring.size() ? s[i + 1] : 1.0};
      seg.ring = r;
      segments.push_back(seg);
    }
  }
  if (options.clip_to_view) {
    const auto& v = options.view;
    const Vector2d c[4] = {v.corner(v.BottomLeft), v.corner(v.BottomRight), v.corner(v.TopRight),
                           v.corner(v.TopLeft)};
    for (int i = 0; i < 4; ++i) segments.push_back({c[i], c[(i + 1) % 4]});
  }
  segments_size.remember(segments);
  // What other wisps or occluders provably hide: whole wisps are left out of the sweep, hidden
  // cells get no depth seams.
  HiddenParts hidden;
  if (options.cull_hidden || options.depth_seams) {
    const auto tc = Clock::now();
    HiddenWispOptions cull;
    for (const Occluder& o : options.occluders) cull.occluder_max_depth.push_back(o.max_depth);
    hidden = hidden_wisps(wisps, segments, cull);
    if (options.cull_hidden) {
      const size_t before = segments.size();
      segments.erase(std::remove_if(segments.begin(), segments.end(),
                                    [&](const auto& s) {
                                      return s.wisp >= 0 && s.wisp < int(wisps.size()) &&
                                             hidden.wisps[s.wisp];
                                    }),
                     segments.end());
      if (options.cut_hidden) cut_hidden_cells(wisps, hidden, segments);
      out.stats.hidden_segments = int(before) - int(segments.size());
      for (const OutlineSegment& s : segments) out.stats.cuts += s.cut;
      for (char h : hidden.wisps) out.stats.hidden_wisps += h;
      out.stats.wisps -= out.stats.hidden_wisps;
    }
    out.stats.cull_ms = ms_since(tc);
  }
  if (options.depth_seams) {
    const auto ts = Clock::now();
    std::vector<char> used(wisps.size(), 0);
    for (const OutlineSegment& s : segments)
      if (s.wisp >= 0 && s.wisp < int(wisps.size())) used[s.wisp] = 1;
    const std::vector<OutlineSegment> seams =
        depth_seams(wisps, used, hidden.cells,
                    options.occluder_seams ? options.occluders : std::vector<Occluder>(), kSeamId,
                    options.clip_to_view ? options.view : Eigen::AlignedBox2d());
    out.stats.seam_segments = int(seams.size());
    segments.insert(segments.end(), seams.begin(), seams.end());
    out.stats.seams_ms = ms_since(ts);
  }
  const PlanarMap map = (options.arrange ? options.arrange : arrange_segments)(segments);
  out.stats.sweep_ms = ms_since(t0);
  const double cpu1 = diffusion::thread_cpu_ms();
  out.stats.sweep_cpu_ms = cpu1 - cpu0;

  const auto t1 = Clock::now();
  Resolver r(wisps, segments, map, options);
  r.propagate_cover();
  r.order_faces();
  r.decide_visibility();
  out.visible = r.visible_intervals(false);
  out.mask = trace_hair_mask(map, r.hair);
  if (options.front_regions) {
    std::vector<int> label(map.faces.size(), -1);
    for (size_t f = 0; f < label.size(); ++f)
      if (r.hair[f] && !r.is_base_front(int(f))) label[f] = r.front[f];
    out.front_regions = trace_regions(map, label, r.n_wisps());
  }
  if (!base.empty()) {
    out.base_visible = r.visible_intervals(true);
    std::vector<int> label(map.faces.size(), -1);
    for (size_t f = 0; f < label.size(); ++f)
      if (r.hair[f] && r.is_base_front(int(f))) label[f] = 0;
    out.base_region = trace_regions(map, label, 1).front();
  }

  std::vector<int> silhouette(map.edge_count(), -1), occlusion(map.edge_count(), -1);
  std::vector<int> cuts(map.edge_count(), -1);
  for (int e = 0; e < map.edge_count(); ++e) {
    const int fl = map.halfedges[2 * e].face, fr = map.halfedges[2 * e + 1].face;
    if (r.hair[fl] != r.hair[fr] && !r.frame_edge(e)) silhouette[e] = r.front[r.hair[fl] ? fl : fr];
    if (silhouette[e] >= 0 && !options.occluders.empty() && r.occluder_edge(e))
      cuts[e] = silhouette[e];
    if (r.hair[fl] && r.hair[fr] && r.front[fl] != r.front[fr] && !r.seam_edge(e)) {
      const int w = r.visible_wisp(e);
      occlusion[e] = w >= 0 ? w : std::min(r.front[fl], r.front[fr]);
    }
  }
  out.silhouette = chain_edges(map, silhouette);
  out.occlusion = chain_edges(map, occlusion);
  out.occluder_cuts = chain_edges(map, cuts);
  std::vector<char> crossing;  // computed once, for the view and the stats
  if (options.keep_faces) out.view = r.view(crossing = r.intersection_flags());
  out.stats.resolve_ms = ms_since(t1);
  out.stats.resolve_cpu_ms = diffusion::thread_cpu_ms() - cpu1;

  out.stats.segments = int(segments.size());
  out.stats.vertices = int(map.vertices.size());
  out.stats.edges = map.edge_count();
  out.stats.faces = int(map.faces.size());
  for (char h : r.hair) out.stats.covered_faces += h;
  if (!options.keep_faces) crossing = r.intersection_flags();
  for (char c : crossing) out.stats.intersections += c;
  return out;
}

}  // namespace wisp::vector
