// Point location in the band cells of a wisp, and the interpolated depth there.
#include "vector/band_depth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

double distance_to_segment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double l = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + l * ab - p).norm();
}

// Crossing-number test (boundary points may go either way; callers tolerate that).
bool inside(const std::array<Vector2d, 4>& q, const Vector2d& p) {
  bool in = false;
  for (int i = 0, j = 3; i < 4; j = i++) {
    if ((q[i].y() > p.y()) != (q[j].y() > p.y())) {
      const double x =
          q[j].x() + (p.y() - q[j].y()) * (q[i].x() - q[j].x()) / (q[i].y() - q[j].y());
      if (p.x() < x) in = !in;
    }
  }
  return in;
}

double distance_to_cell(const std::array<Vector2d, 4>& q, const Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0, j = 3; i < 4; j = i++) d = std::min(d, distance_to_segment(p, q[j], q[i]));
  return d;
}

bool outside(const Eigen::AlignedBox2d& box, const Vector2d& p, double margin) {
  return p.x() < box.min().x() - margin || p.x() > box.max().x() + margin ||
         p.y() < box.min().y() - margin || p.y() > box.max().y() + margin;
}

double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The smallest barycentric coordinate of p in t: >= 0 inside, the more negative the farther out.
double inside_measure(const CellTriangle& t, const Vector2d& p) {
  const Vector2d e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0], q = p - t.v[0];
  const double area = cross(e1, e2);
  if (area == 0) return -INFINITY;
  const double l1 = cross(q, e2) / area, l2 = cross(e1, q) / area;
  return std::min({l1, l2, 1 - l1 - l2});
}

CellTriangle triangle(const Vector2d& a, const Vector2d& b, const Vector2d& c, double za, double zb,
                      double zc) {
  CellTriangle t{{a, b, c}, {za, zb, zc}};
  const Vector2d e1 = b - a, e2 = c - a;
  const double area = cross(e1, e2);
  if (area != 0) {
    t.grad = ((zb - za) * Vector2d(e2.y(), -e2.x()) + (zc - za) * Vector2d(-e1.y(), e1.x())) / area;
    t.offset = za - t.grad.dot(a);
  } else {
    t.offset = (za + zb + zc) / 3;
  }
  return t;
}

// The depth in cell i at p, from the triangle that p lies in (or is nearest to being in), and the
// centre parameter by the projection onto the cell's centre segment.
BandHit hit(const Wisp& w, const BandCells& c, int i, const Vector2d& p) {
  const Section &a = w.sections[i], &b = w.sections[i + 1];
  const Vector2d ab = b.centre - a.centre;
  const double len2 = ab.squaredNorm();
  const double l = len2 > 0 ? std::clamp((p - a.centre).dot(ab) / len2, 0.0, 1.0) : 0.5;
  const auto& t = c.triangles[i];
  const CellTriangle& in = inside_measure(t[0], p) >= inside_measure(t[1], p) ? t[0] : t[1];
  const double lo = std::min(a.depth, b.depth), hi = std::max(a.depth, b.depth);
  return {std::clamp(in.depth(p), lo, hi), a.t + l * (b.t - a.t)};
}

}  // namespace

bool cell_triangles(const Wisp& w, int i, std::array<CellTriangle, 2>& out) {
  const Section &a = w.sections[i], &b = w.sections[i + 1];
  const Vector2d &l0 = a.left, &l1 = b.left, &r1 = b.right, &r0 = a.right;
  // The diagonal l0-r1 when l1 and r0 lie on either side of it, else l1-r0: one of the two lies
  // inside any simple quadrilateral.
  const Vector2d d = r1 - l0;
  const int pl0 = 2 * i, pr0 = 2 * i + 1, pl1 = 2 * i + 2, pr1 = 2 * i + 3;
  if (cross(d, l1 - l0) * cross(d, r0 - l0) < 0) {
    out[0] = triangle(l0, l1, r1, a.depth, b.depth, b.depth);
    out[1] = triangle(l0, r1, r0, a.depth, b.depth, a.depth);
    out[0].point = {pl0, pl1, pr1}, out[1].point = {pl0, pr1, pr0};
  } else {
    out[0] = triangle(l0, l1, r0, a.depth, b.depth, a.depth);
    out[1] = triangle(l1, r1, r0, b.depth, b.depth, a.depth);
    out[0].point = {pl0, pl1, pr0}, out[1].point = {pl1, pr1, pr0};
  }
  return cross(out[0].v[1] - out[0].v[0], out[0].v[2] - out[0].v[0]) != 0 ||
         cross(out[1].v[1] - out[1].v[0], out[1].v[2] - out[1].v[0]) != 0;
}

// Monotone in c, so a box [lo, hi] reaches every slab from slab_of(lo) to slab_of(hi), and a
// point inside the box lies in one of them.
int BandCells::slab_of(double c) const {
  const int last = slabs - 1;
  const double k = std::floor((c - slab_min) * slab_scale);
  return k <= 0 ? 0 : k >= last ? last : int(k);
}

BandCells band_cells(const Wisp& w) {
  BandCells c;
  const int cells = int(w.sections.size()) - 1;
  c.quads.reserve(cells);
  c.boxes.reserve(cells);
  c.triangles.reserve(cells);
  Eigen::AlignedBox2d all;
  for (int i = 0; i < cells; ++i) {
    const Section &a = w.sections[i], &b = w.sections[i + 1];
    c.quads.push_back({a.left, b.left, b.right, a.right});
    cell_triangles(w, i, c.triangles.emplace_back());
    Eigen::AlignedBox2d box(a.left);
    for (const Vector2d& q : {b.left, b.right, a.right}) box.extend(q);
    c.boxes.push_back(box);
    all.extend(box);
  }
  // About one slab per cell: a wisp's cells follow its centre, so most slabs hold a few.
  const int slabs = c.slabs = std::max(1, cells);
  c.axis = cells > 0 && all.sizes().y() > all.sizes().x() ? 1 : 0;
  const double extent = cells > 0 ? all.sizes()[c.axis] : 0;
  c.slab_min = cells > 0 ? all.min()[c.axis] : 0;
  c.slab_scale = extent > 0 && std::isfinite(extent) ? slabs / extent : 0;
  c.slab_begin.assign(slabs + 2, 0);
  for (int i = 0; i < cells; ++i)
    for (int k = c.slab_of(c.boxes[i].min()[c.axis]); k <= c.slab_of(c.boxes[i].max()[c.axis]); ++k)
      ++c.slab_begin[k + 2];
  for (int k = 2; k < slabs + 2; ++k) c.slab_begin[k] += c.slab_begin[k - 1];
  c.slab_cells.resize(c.slab_begin[slabs + 1]);
  for (int i = 0; i < cells; ++i)
    for (int k = c.slab_of(c.boxes[i].min()[c.axis]); k <= c.slab_of(c.boxes[i].max()[c.axis]); ++k)
      c.slab_cells[c.slab_begin[k + 1]++] = i;
  c.slab_begin.pop_back();
  return c;
}

BandHit band_depth(const Wisp& w, const BandCells& c, const Vector2d& p) {
  std::optional<BandHit> best;
  const int cells = int(c.quads.size());
  const int k = c.slab_of(p[c.axis]);
  for (int j = c.slab_begin[k]; j < c.slab_begin[k + 1]; ++j) {
    const int i = c.slab_cells[j];
    if (outside(c.boxes[i], p, 0) || !inside(c.quads[i], p)) continue;
    const BandHit h = hit(w, c, i, p);
    if (!best || h.depth < best->depth) best = h;
  }
  if (best) return *best;
  // Rare: p is a rounding error outside every cell. The nearest cell decides.
  int nearest = 0;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < cells; ++i) {
    const double d = distance_to_cell(c.quads[i], p);
    if (d < nearest_distance) nearest_distance = d, nearest = i;
  }
  return hit(w, c, nearest, p);
}

BandHit band_depth(const Wisp& w, const Vector2d& p) {
  return band_depth(w, band_cells(w), p);
}

std::optional<BandHit> band_depth_inside(const Wisp& w, const BandCells& c, const Vector2d& p,
                                         double margin) {
  std::optional<BandHit> best;
  const int k = c.slab_of(p[c.axis]);
  for (int j = c.slab_begin[k]; j < c.slab_begin[k + 1]; ++j) {
    const int i = c.slab_cells[j];
    if (outside(c.boxes[i], p, -margin) || !inside(c.quads[i], p) ||
        distance_to_cell(c.quads[i], p) < margin)
      continue;
    const BandHit h = hit(w, c, i, p);
    if (!best || h.depth < best->depth) best = h;
  }
  return best;
}

std::optional<BandHit> band_depth_inside(const Wisp& w, const Vector2d& p, double margin) {
  return band_depth_inside(w, band_cells(w), p, margin);
}

}  // namespace wisp::vector
