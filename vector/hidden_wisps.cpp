// The cull of hidden wisps before the sweep (see hidden_wisps.hpp).
//
// What a culled wisp d could change. Everything the arrangement gives downstream follows from each
// face's front-most wisp: the visible intervals (an outline piece shows where its wisp is
// front-most on one side), the hair mask (faces whose front is a wisp or the hair base), the
// silhouette, occlusion and occluder-cut lines (edges whose two faces differ in hair or front),
// the front regions and, through the faces' fronts only, the visible regions that highlights,
// inner curves and hatching are clipped to. No reader asks for the second wisp of a face: the
// colour beyond a visible outline is the shadow colour or a highlight of a visible wisp. So a wisp
// that is front-most on no face has no visible interval, no front region and is no face's front.
// Taking its outline out merges faces whose covers differ only in d. What can then move:
//  - the resolver decides a face's front at one sample point. Between wisps that decides the
//    whole face, since the depth seams split faces where two wisps swap order (depth_seams.hpp);
//    but where a wisp and an occluder swap inside a merged face, or in the curl rule's one test
//    per edge, the sample may pick otherwise than the pieces' samples did;
//  - the vertices d's outline put on other outlines go: the same polylines and mask polygons
//    with points that lay on them to rounding left out.
// Neither is more right with d than without; docs/vector.md 5b measures both.
//
// Hidden cells. A cell of a kept wisp whose least depth is beyond front[c] (below) for every
// square c its box meets lies, at each of its points, behind whatever covers that square; a
// depth seam of it has both wisps' depths there, so it lies behind too and can change no face's
// front. Where such a seam is left out, the seam of the cells around it ends inside that cover,
// whose outline it has crossed: the faces outside the cover are still split.
//
// The grid test. The plane is cut into squares of `square_px`; every test below uses each square
// grown by kEps, far above the rounding of any double computed here, so a decision about the
// grown square holds for every point that rounds into the square. Per wisp and square:
//  - edge: an outline segment of the wisp meets the square. Where none does, the wisp's winding
//    number is the same over the whole square: the one at its centre (scanline crossings);
//  - covers: no edge and winding != 0: every face meeting the square has the wisp in its cover;
//  - reaches: edge or winding != 0: a face with the wisp in its cover can only meet such squares;
//  - lo, hi: the smallest and largest depth over the square of the band cells that meet it.
//    band_depth (the resolver's depth) is affine over each of a cell's two triangles, in a cell
//    that contains the point or, for a point a rounding error outside, the nearest one, and lies
//    between the cell's two sections' depths: so the wisp's depth lies in [lo, hi], taken over
//    the cells whose boxes meet the square (to rounding, which the margin absorbs).
// An occluder covers the squares inside its ring (the same winding test), with its own upper
// bound of depth over the square for hi (sim::SurfaceRays::max_depth for the body).
// front[c] = the smallest hi of whatever covers square c. A wisp d is culled when every square it
// reaches has lo(d) > front[c] (with a relative margin of 1e-9). Then at the sample point p of any
// face f with d in its cover, p lies in a square c that d reaches; the wisp or occluder k with
// hi(k) = front[c] covers c, so k is in f's cover, and depth_k(p) <= front[c] < depth_d(p): d is
// not f's front. A wisp k proving a cull is never culled itself (its lo over c is at most its hi,
// which is front[c]), so the culls of one call hold together. The test is made per square, not per
// occluding wisp: hidden wisps are mostly hidden by several wisps together, each over a part.
#include "vector/hidden_wisps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

constexpr double kEps = 1e-3;  // px by which squares grow for every test
constexpr double kInf = std::numeric_limits<double>::infinity();

// Whether segment ab meets the closed box [lo, hi] (Liang-Barsky clipping).
bool meets(const Vector2d& a, const Vector2d& b, const Vector2d& lo, const Vector2d& hi) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 2; ++k) {
    const double d = b[k] - a[k];
    if (d == 0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double u = (lo[k] - a[k]) / d, v = (hi[k] - a[k]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

struct Grid {
  Vector2d origin;
  double side = 1;
  int nx = 0, ny = 0;
  int col(double x) const {
    return std::clamp(int(std::floor((x - origin.x()) / side)), 0, nx - 1);
  }
  int row(double y) const {
    return std::clamp(int(std::floor((y - origin.y()) / side)), 0, ny - 1);
  }
  Vector2d lo(int i, int j) const {
    return origin + side * Vector2d(i, j) - Vector2d::Constant(kEps);
  }
  Vector2d hi(int i, int j) const {
    return origin + side * Vector2d(i + 1, j + 1) + Vector2d::Constant(kEps);
  }
  double centre_x(int i) const { return origin.x() + (i + 0.5) * side; }
  double centre_y(int j) const { return origin.y() + (j + 0.5) * side; }
};

// One wisp's squares over its window [i0, i0 + w) x [j0, j0 + h) of the grid.
struct WispSquares {
  int i0 = 0, j0 = 0, w = 0, h = 0;
  std::vector<char> edge, covers, reaches;
  std::vector<double> lo, hi;
  int at(int i, int j) const { return (j - j0) * w + (i - i0); }
};

// Visits the squares of the grid that segment ab meets (grown by kEps), clamped to [i0, i1] x
// [j0, j1].
template <class F>
void for_squares_met(const Grid& g, const Vector2d& a, const Vector2d& b, int i0, int i1, int j0,
                     int j1, F&& fn) {
  const int c0 = std::max(i0, g.col(std::min(a.x(), b.x()) - kEps));
  const int c1 = std::min(i1, g.col(std::max(a.x(), b.x()) + kEps));
  const int r0 = std::max(j0, g.row(std::min(a.y(), b.y()) - kEps));
  const int r1 = std::min(j1, g.row(std::max(a.y(), b.y()) + kEps));
  for (int j = r0; j <= r1; ++j)
    for (int i = c0; i <= c1; ++i)
      if (meets(a, b, g.lo(i, j), g.hi(i, j))) fn(i, j);
}

// Marks the squares of q's window that the segments meet (edge), and those they do not meet
// where their winding number (at the centre) is nonzero: covered (covers), or reached at all
// (reaches: edge or winding != 0). A square needs a depth bound (hi) to count as covered.
void outline_squares(const Grid& g, const std::vector<OutlineSegment>& segs,
                     const std::vector<int>& mine, WispSquares& q, int i1, int j1) {
  // The winding number at every square's centre: a crossing of
  // the centre row at x counts for the centres left of x (the ray to +x), +1 going up, -1 down.
  std::vector<int> winding(size_t(q.w + 1) * q.h, 0);  // per row: differences, one slot spare
  const auto slot = [&](int i, int j) { return size_t(j - q.j0) * (q.w + 1) + (i - q.i0); };
  for (int s : mine) {
    const Vector2d &a = segs[s].a, &b = segs[s].b;
    for_squares_met(g, a, b, q.i0, i1, q.j0, j1, [&](int i, int j) { q.edge[q.at(i, j)] = 1; });
    if (a.y() == b.y()) continue;
    const int r0 = std::max(q.j0, g.row(std::min(a.y(), b.y())) - 1);
    const int r1 = std::min(j1, g.row(std::max(a.y(), b.y())) + 1);
    for (int j = r0; j <= r1; ++j) {
      const double y = g.centre_y(j);
      if ((a.y() > y) == (b.y() > y)) continue;
      const double x = a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      int last = std::clamp(int(std::floor((x - g.origin.x()) / g.side - 0.5)), q.i0 - 1, i1);
      while (last + 1 <= i1 && g.centre_x(last + 1) < x) ++last;
      while (last >= q.i0 && !(g.centre_x(last) < x)) --last;
      if (last < q.i0) continue;
      const int dir = b.y() > a.y() ? 1 : -1;
      winding[slot(q.i0, j)] += dir;
      winding[slot(last + 1, j)] -= dir;
    }
  }
  for (int j = q.j0; j <= j1; ++j) {
    int sum = 0;
    for (int i = q.i0; i <= i1; ++i) {
      sum += winding[slot(i, j)];
      const int at = q.at(i, j);
      q.covers[at] = sum != 0 && !q.edge[at] && q.hi[at] > -kInf;
      q.reaches[at] = sum != 0 || q.edge[at];
    }
  }
}

WispSquares wisp_squares(const Grid& g, const Wisp& wisp, const std::vector<OutlineSegment>& segs,
                         const std::vector<int>& mine) {
  Eigen::AlignedBox2d box;
  for (int s : mine) box.extend(segs[s].a), box.extend(segs[s].b);
  for (const Section& s : wisp.sections) box.extend(s.left), box.extend(s.right);
  WispSquares q;
  q.i0 = g.col(box.min().x() - kEps), q.j0 = g.row(box.min().y() - kEps);
  const int i1 = g.col(box.max().x() + kEps), j1 = g.row(box.max().y() + kEps);
  q.w = i1 - q.i0 + 1, q.h = j1 - q.j0 + 1;
  const size_t n = size_t(q.w) * q.h;
  q.edge.assign(n, 0);
  q.covers.assign(n, 0);
  q.reaches.assign(n, 0);
  q.lo.assign(n, kInf);
  q.hi.assign(n, -kInf);

  // Depth bounds from the band cells whose boxes meet each square: a cell's depth lies between
  // its two sections' depths (vector/band_depth.hpp), and every cell holding a point of the square
  // has a box that meets it. (A cell's box meeting a square it does not only loosens the bounds.)
  for (size_t k = 0; k + 1 < wisp.sections.size(); ++k) {
    const Section &a = wisp.sections[k], &b = wisp.sections[k + 1];
    Eigen::AlignedBox2d cell(a.left);
    for (const Vector2d& p : {b.left, b.right, a.right}) cell.extend(p);
    const double zlo = std::min(a.depth, b.depth), zhi = std::max(a.depth, b.depth);
    const int c0 = g.col(cell.min().x() - kEps), c1 = g.col(cell.max().x() + kEps);
    const int r0 = g.row(cell.min().y() - kEps), r1 = g.row(cell.max().y() + kEps);
    for (int j = std::max(r0, q.j0); j <= std::min(r1, j1); ++j)
      for (int i = std::max(c0, q.i0); i <= std::min(c1, i1); ++i) {
        const int at = q.at(i, j);
        q.lo[at] = std::min(q.lo[at], zlo);
        q.hi[at] = std::max(q.hi[at], zhi);
      }
  }

  outline_squares(g, segs, mine, q, i1, j1);
  return q;
}

}  // namespace

HiddenParts hidden_wisps(const std::vector<Wisp>& wisps,
                         const std::vector<OutlineSegment>& segments,
                         const HiddenWispOptions& options) {
  const int n = int(wisps.size());
  HiddenParts out;
  out.wisps.assign(n, 0);
  out.cells.resize(n);
  std::vector<char>& hidden = out.wisps;
  if (n == 0 || segments.empty()) return out;

  std::vector<std::vector<int>> mine(n);
  Eigen::AlignedBox2d all;
  for (int s = 0; s < int(segments.size()); ++s) {
    all.extend(segments[s].a), all.extend(segments[s].b);
    if (segments[s].wisp >= 0 && segments[s].wisp < n) mine[segments[s].wisp].push_back(s);
  }
  for (int w = 0; w < n; ++w)
    for (const Section& s : wisps[w].sections)
      if (!mine[w].empty()) all.extend(s.left), all.extend(s.right);
  if (!all.sizes().allFinite()) return out;

  // The squares tile the segments' box with one square to spare on each side; a box too large
  // for a few million squares gets larger ones.
  Grid g;
  g.side = options.square_px;
  while ((all.sizes().x() / g.side + 3) * (all.sizes().y() / g.side + 3) > 4e6) g.side *= 2;
  g.origin = all.min() - Vector2d::Constant(g.side);
  g.nx = int(std::ceil(all.sizes().x() / g.side)) + 2;
  g.ny = int(std::ceil(all.sizes().y() / g.side)) + 2;
  const size_t squares = size_t(g.nx) * g.ny;

  std::vector<WispSquares> sq(n);
  std::vector<double> front(squares, kInf);
  for (int w = 0; w < n; ++w) {
    if (mine[w].empty()) continue;
    sq[w] = wisp_squares(g, wisps[w], segments, mine[w]);
    const WispSquares& q = sq[w];
    for (int j = q.j0; j < q.j0 + q.h; ++j)
      for (int i = q.i0; i < q.i0 + q.w; ++i) {
        const int at = q.at(i, j);
        if (q.covers[at]) {
          double& f = front[size_t(j) * g.nx + i];
          f = std::min(f, q.hi[at]);
        }
      }
  }

  // Occluders cover the squares inside their rings, as near as their depth bound there. The
  // bounds cost ray casts, so they are asked only where the wisps' front does not settle a square,
  // once per square.
  const int occluders = std::min(int(options.occluder_max_depth.size()), 8);
  std::vector<std::uint8_t> inside(occluders > 0 ? squares : 0, 0);  // bit k: occluder k covers
  for (int k = 0; k < occluders; ++k) {
    std::vector<int> ring;
    Eigen::AlignedBox2d box;
    for (int s = 0; s < int(segments.size()); ++s)
      if (segments[s].wisp == n + k) ring.push_back(s), box.extend(segments[s].a);
    if (ring.empty() || !options.occluder_max_depth[k]) continue;
    WispSquares q;
    q.i0 = g.col(box.min().x() - kEps), q.j0 = g.row(box.min().y() - kEps);
    const int i1 = g.col(box.max().x() + kEps), j1 = g.row(box.max().y() + kEps);
    q.w = i1 - q.i0 + 1, q.h = j1 - q.j0 + 1;
    const size_t m = size_t(q.w) * q.h;
    q.edge.assign(m, 0), q.covers.assign(m, 0), q.reaches.assign(m, 0);
    q.hi.assign(m, 0);  // any finite value: covers then follows the ring alone
    outline_squares(g, segments, ring, q, i1, j1);
    for (int j = q.j0; j <= j1; ++j)
      for (int i = q.i0; i <= i1; ++i)
        if (q.covers[q.at(i, j)]) inside[size_t(j) * g.nx + i] |= std::uint8_t(1u << k);
  }
  std::vector<char> asked(inside.size(), 0);
  const auto nearest = [&](size_t c, int i, int j) {
    if (inside.empty() || !inside[c] || asked[c]) return front[c];
    asked[c] = 1;
    const Eigen::AlignedBox2d box(g.lo(i, j), g.hi(i, j));
    for (int k = 0; k < occluders; ++k)
      if (inside[c] & (1u << k)) front[c] = std::min(front[c], options.occluder_max_depth[k](box));
    return front[c];
  };

  const auto behind = [](double lo, double f) {
    return lo < kInf && f < kInf && lo > f + 1e-9 * (1 + std::abs(f));
  };
  for (int d = 0; d < n; ++d) {
    if (mine[d].empty()) continue;
    const WispSquares& q = sq[d];
    bool culled = true;
    for (int j = q.j0; j < q.j0 + q.h && culled; ++j)
      for (int i = q.i0; i < q.i0 + q.w && culled; ++i) {
        const int at = q.at(i, j);
        if (!q.reaches[at]) continue;
        const size_t c = size_t(j) * g.nx + i;
        culled = behind(q.lo[at], front[c]) || behind(q.lo[at], nearest(c, i, j));
      }
    hidden[d] = culled;
  }

  // Cells: every square the cell's box meets. A cell's depth is at least its sections' least.
  for (int d = 0; d < n; ++d) {
    if (mine[d].empty()) continue;
    const std::vector<Section>& sec = wisps[d].sections;
    std::vector<char>& cells = out.cells[d];
    cells.assign(sec.size() - 1, hidden[d]);  // a hidden wisp's cells are all hidden
    if (hidden[d]) continue;
    for (size_t k = 0; k + 1 < sec.size(); ++k) {
      const Section &a = sec[k], &b = sec[k + 1];
      Eigen::AlignedBox2d cell(a.left);
      for (const Vector2d& p : {b.left, b.right, a.right}) cell.extend(p);
      const double lo = std::min(a.depth, b.depth);
      const int c0 = g.col(cell.min().x() - kEps), c1 = g.col(cell.max().x() + kEps);
      const int r0 = g.row(cell.min().y() - kEps), r1 = g.row(cell.max().y() + kEps);
      bool behind_all = true;
      for (int j = r0; j <= r1 && behind_all; ++j)
        for (int i = c0; i <= c1 && behind_all; ++i) {
          const size_t c = size_t(j) * g.nx + i;
          behind_all = behind(lo, front[c]) || behind(lo, nearest(c, i, j));
        }
      cells[k] = behind_all;
    }
  }
  return out;
}

}  // namespace wisp::vector
