// The segment arrangement through CGAL (wisp_vector_exact): one aggregated sweep (CGAL::insert over
// all segments), then a copy of the DCEL into PlanarMap's index arrays. Rendering uses our own
// (segment_arrangement.cpp); this is the reference its tests and `wisp-bench arrangement` compare.
#include <CGAL/number_utils.h>

#include <cmath>

#include "vector/arrangement.hpp"
#include "vector/arrangement_cgal.hpp"
#include "vector/planar_map.hpp"

namespace wisp::vector {

namespace {

// CGAL orders points xy-lexicographically; a segment is "left to right" when a < b that way.
bool left_to_right(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
}

// CGAL::to_double(p.x()) without building a lazy x() node: the same rule as Lazy_exact_nt's
// To_double (the interval's value when it is precise to 1e-5, else the exact value rounded).
double to_double(const cgal::Point& p, int axis) {
  const CGAL::Interval_nt<false> approx = axis == 0 ? p.approx().x() : p.approx().y();
  double r;
  if (CGAL::fit_in_double(approx, r)) return r;
  if (CGAL::has_smaller_relative_precision(approx,
                                           cgal::Kernel::FT::get_relative_precision_of_to_double()))
    return CGAL::to_double(approx);
  return CGAL::to_double(axis == 0 ? p.x() : p.y());
}

}  // namespace

PlanarMap arrange_segments_cgal(const std::vector<OutlineSegment>& segments) {
  using namespace cgal;
  // Each segment from two points, not from a Segment_2 (whose two vertex() calls are two more
  // nodes of the lazy kernel's DAG), and an outline's consecutive segments share the point where
  // they meet: the sweep's cost is mostly allocation, and this is half the input's nodes.
  std::vector<Traits::Curve_2> curves;
  curves.reserve(segments.size());
  Point end;  // the end of the last segment added, at `end_at`
  Eigen::Vector2d end_at(NAN, NAN);
  for (int i = 0; i < int(segments.size()); ++i) {
    const OutlineSegment& s = segments[i];
    if (s.a == s.b) continue;
    const Point a = s.a == end_at ? end : Point(s.a.x(), s.a.y());
    end = Point(s.b.x(), s.b.y());
    end_at = s.b;
    curves.emplace_back(SegmentTraits::Curve_2(a, end), i);
  }
  Arrangement arr;
  CGAL::insert(arr, curves.begin(), curves.end());

  PlanarMap map;
  map.vertices.reserve(arr.number_of_vertices());
  int index = 0;
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
    v->set_data(index++);
    map.vertices.emplace_back(to_double(v->point(), 0), to_double(v->point(), 1));
  }
  index = 0;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->set_data(index++);
  index = 0;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    e->set_data(2 * index);
    e->twin()->set_data(2 * index + 1);
    ++index;
  }

  map.halfedges.resize(2 * arr.number_of_edges());
  map.source_begin.reserve(arr.number_of_edges() + 1);
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    for (auto h : {Arrangement::Halfedge_handle(e), e->twin()}) {
      map.halfedges[h->data()] = {h->target()->data(), h->next()->data(), h->face()->data()};
    }
    const bool edge_left_to_right = e->direction() == CGAL::ARR_LEFT_TO_RIGHT;
    map.source_begin.push_back(int(map.sources.size()));
    for (int segment : e->curve().data()) {
      const OutlineSegment& s = segments[segment];
      map.sources.push_back({segment, left_to_right(s.a, s.b) == edge_left_to_right});
    }
  }
  map.source_begin.push_back(int(map.sources.size()));

  map.faces.resize(arr.number_of_faces());
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    PlanarMap::Face& face = map.faces[f->data()];
    if (f->is_unbounded())
      map.unbounded_face = f->data();
    else
      face.outer = f->outer_ccb()->data();
    face.holes_begin = int(map.holes.size());
    for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole)
      map.holes.push_back((*hole)->data());
    face.holes_end = int(map.holes.size());
  }
  return map;
}

}  // namespace wisp::vector
