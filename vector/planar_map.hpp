// Private to vector/: the plain form of the CGAL arrangement. arrangement_cgal.cpp inserts the
// flattened outline segments into an exact arrangement and copies its doubly connected edge list
// out into these index-based arrays, so everything downstream (coverage, depth order, visibility,
// hair mask, debug view) is ordinary C++ that compiles fast and never sees a CGAL type.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "vector/wisp.hpp"

namespace wisp::vector {

// One input segment of the arrangement: a piece of a flattened wisp outline, directed along the
// outline (wisp interior on its left in CGAL's orientation), or a side of the view frame (wisp
// -1). Outline parameter and depth are linear along it. Occluders and the hair base follow the
// wisps' indices; a segment of the hair base knows its path (`ring`) and that path's parameter.
// A cut is a line across a wisp's band where the arrangement left out the band's hidden cells
// beyond it (ArrangementOptions::cut_hidden): no outline runs there, so it has no outline
// parameter (s0 == s1).
struct OutlineSegment {
  Eigen::Vector2d a, b;
  int wisp = -1;
  Side side = Side::Left;
  double s0 = 0, s1 = 0;
  double z0 = 0, z1 = 0;
  int ring = 0;
  bool cut = false;
};

// Index-based doubly connected edge list. Edge e owns halfedges 2e and 2e+1 (twins: h ^ 1). A
// halfedge's face lies to its left; it runs from target(h ^ 1) to target(h).
struct PlanarMap {
  struct Halfedge {
    int target = -1;
    int next = -1;
    int face = -1;
  };
  // A source of an edge: the input segment and whether it runs like the edge's halfedge 2e.
  struct Source {
    int segment = -1;
    bool along = true;
  };
  struct Face {
    int outer = -1;  // first halfedge of the outer boundary, -1 for the unbounded face
    int holes_begin = 0, holes_end = 0;  // range in `holes` (first halfedge of each inner boundary)
  };

  std::vector<Eigen::Vector2d> vertices;  // rounded from the exact coordinates
  std::vector<Halfedge> halfedges;
  std::vector<int> source_begin;  // edge e's sources: sources[source_begin[e] .. [e+1])
  std::vector<Source> sources;
  std::vector<Face> faces;
  std::vector<int> holes;
  int unbounded_face = -1;

  int edge_count() const { return int(halfedges.size() / 2); }
  int source(int h) const { return halfedges[h ^ 1].target; }
};

// The exact arrangement of the segments (vector/segment_arrangement.cpp): their ends snapped to a
// grid of 2^-k px with every coordinate below 2^29 units (k = 17 at 1024 px), then exact integer
// predicates throughout. Zero-length segments (after snapping) are skipped. Deterministic:
// indices depend only on the input. Throws std::invalid_argument on a non-finite coordinate.
PlanarMap arrange_segments(const std::vector<OutlineSegment>& segments);
// CGAL's, the reference: arrange_segments_cgal in vector/arrangement.hpp.

}  // namespace wisp::vector
