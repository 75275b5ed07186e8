// Exact visibility of wisps: the planar arrangement of all wisp outlines (CGAL, exact segments)
// and what it decides. This replaces Faraj's pairwise intersection rule (2009, section 3.3.2),
// which fails on wavy wisps, containment and cyclic overlaps, with one general rule:
//  - coverage: each face knows the winding number of every wisp around it, propagated from the
//    unbounded face across edges (crossing an outline changes its wisp's winding by one);
//  - depth order: the front-most covering wisp of a face is the one nearest the eye at one
//    interior sample point of the face (depth inside a wisp is that of its centre cross-section);
//    the faces are split where two covering wisps swap depth order, or a wisp and an occluder
//    (vector/depth_seams.hpp), so that sample decides every point of the face;
//  - visibility: an outline piece is visible where its wisp is front-most on either side of it
//    (and no other pass of the same wisp lies in front of it, for curls that overlap themselves).
// From these follow the hair mask (union of covered faces, holes kept), the silhouette and the
// occlusion boundaries as ink polylines, and per outline the visible parameter intervals.
// The hair base (vector/hair_base.hpp), when given, lies behind every wisp and in front of the
// head it is drawn on: a face inside it with no wisp in front of the occluders is hair, the
// base's own, unless an occluder is nearer than the base there (the neck, the shoulders).
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <utility>
#include <vector>

#include "vector/arrangement_view.hpp"
#include "vector/hair_base.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

// Something opaque that is not hair, in front of some wisps and behind others: the head and the
// body. Its silhouette (a simple closed ring, either orientation) enters the arrangement; a face
// inside it belongs to the occluder wherever the occluder is nearer the eye than every wisp
// covering the face. Hair that passes behind it is then cut exactly along its silhouette.
struct Occluder {
  std::vector<Eigen::Vector2d> ring;
  // Distance from the eye to the occluder's surface seen through a pixel; +infinity where the
  // ray misses it. Called once per face inside the ring.
  std::function<double(const Eigen::Vector2d&)> depth;
  // Optional: an upper bound of `depth` over a box, +infinity where none is known. With it the
  // occluder can prove wisps behind it hidden before the sweep (ArrangementOptions::cull_hidden).
  std::function<double(const Eigen::AlignedBox2d&)> max_depth;
};

struct OutlineSegment;
struct PlanarMap;
// Arranges the flattened outline segments (vector/planar_map.hpp).
using SegmentArrangement = PlanarMap (*)(const std::vector<OutlineSegment>&);

struct ArrangementOptions {
  // The image rectangle. With clipping on, its sides enter the arrangement: nothing outside
  // counts as hair or as visible, and wisps wholly outside are left out before the sweep.
  Eigen::AlignedBox2d view{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  bool clip_to_view = true;
  // Fill WispArrangement::view: every face, edge and vertex as plain geometry, with the faces'
  // cover and front-most wisp. Curves inside wisps are clipped to these faces (shade_hair throws
  // without them), and the inspector draws them.
  bool keep_faces = false;
  bool front_regions = false;  // fill WispArrangement::front_regions
  // Split the faces along the lines where two overlapping wisps swap depth order
  // (vector/depth_seams.hpp): then the one depth sample that decides a face's front wisp decides
  // it for every point of the face, and the picture no longer depends on how the outlines happen
  // to subdivide the hair. Seams of cells that something nearer provably hides are left out.
  bool depth_seams = true;
  // With depth_seams, split them also where a wisp passes behind an occluder (the head, the
  // body; vector/depth_seams.hpp): the hair's edge against the body then no longer
  // depends on the subdivision either, to within the occluder's curvature over a wisp's triangle.
  bool occluder_seams = true;
  // Leave out before the sweep the wisps that other wisps or occluders provably hide everywhere
  // (vector/hidden_wisps.hpp): no wisp that could be a face's front is dropped, and the faces and
  // edges inside the hair are fewer (about half the sweep's intersections on the curly scene).
  // With the depth seams no face's front depends on the outlines left out (docs/vector.md 5b).
  bool cull_hidden = true;
  // With cull_hidden, also leave out the hidden cells of the wisps kept (those of their cells
  // that something nearer covers wholly, vector/hidden_wisps.hpp): each wisp enters the sweep as
  // the outlines of its runs of other cells, closed by lines across the band (cuts). About half
  // the cells of the wisps kept are hidden on the shipped scenes.
  bool cut_hidden = true;
  std::vector<Occluder> occluders;
  HairBase base;  // empty: none
  // Null: ours (exact predicates on snapped input). `wisp-bench arrangement` passes
  // arrange_segments_cgal to time CGAL's sweep on the same segments.
  SegmentArrangement arrange = nullptr;
};

// A polygon with holes, vertices in pixels. The outer boundary turns counter-clockwise in (x, y)
// (clockwise on screen, where y points down); holes turn the other way.
struct MaskPolygon {
  std::vector<Eigen::Vector2d> outer;
  std::vector<std::vector<Eigen::Vector2d>> holes;
};

// Where hair is: the union of covered faces inside the view.
struct HairMask {
  std::vector<MaskPolygon> polygons;
};

// A polyline for ink outlines; `wisp` is the wisp whose visible outline it follows.
struct InkLine {
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
  int wisp = -1;
};

struct ArrangementStats {
  int wisps = 0;  // wisps inserted (after culling those wholly outside the view or hidden)
  int hidden_wisps = 0, hidden_segments = 0;  // left out as hidden (cull_hidden, cut_hidden)
  int cuts = 0;                               // lines across bands closing their kept runs
  int segments = 0;                           // input segments, frame sides included
  int seam_segments = 0;                      // of them, depth seams (vector/depth_seams.hpp)
  int vertices = 0, edges = 0, faces = 0;
  int covered_faces = 0;
  int intersections = 0;  // vertices where outlines (or depth seams) cross or touch
  double sweep_ms = 0;    // the sweep, and the cull and the depth seams before it
  double cull_ms = 0;     // the cull alone (the hidden wisps and cells)
  double seams_ms = 0;    // the depth seams
  double resolve_ms = 0;  // coverage, depth order, visibility, mask, polylines
  double sweep_cpu_ms = 0, resolve_cpu_ms = 0;  // the same as CPU time of the calling thread
};

struct WispArrangement {
  // Per input wisp: the visible parts of its outline as sorted, disjoint [s0, s1] intervals of
  // the outline parameter (the layout of diffusion::DiffusionCurve::active; empty: all hidden).
  std::vector<std::vector<std::pair<double, double>>> visible;
  HairMask mask;
  std::vector<InkLine> silhouette;  // boundary between hair and no hair (not the view frame)
  std::vector<InkLine> occlusion;   // where the front-most wisp changes inside the hair
  // The silhouette's edges that run along an occluder: where the body in front cuts the hair.
  std::vector<InkLine> occluder_cuts;
  ArrangementStats stats;
  ArrangementView view;  // only with ArrangementOptions::keep_faces
  // Per input wisp: where it is the front-most wisp (hair faces only), as polygons with holes;
  // together they tile the hair mask. Only with ArrangementOptions::front_regions.
  std::vector<HairMask> front_regions;
  // Per path of the hair base: its visible parameter intervals (where the base is front-most on
  // either side). And where the base is front-most, as polygons with holes.
  std::vector<std::vector<std::pair<double, double>>> base_visible;
  HairMask base_region;
};

// Throws std::invalid_argument when clipping is on and the view is empty or not finite.
WispArrangement build_arrangement(const std::vector<Wisp>& wisps,
                                  const ArrangementOptions& options);

// The view rectangle of a frame of the given size: [0,width] x [0,height].
Eigen::AlignedBox2d image_rect(int width, int height);

// Topology of the same outlines as exact cubic Bezier curves (CGAL's Arr_Bezier_curve_traits_2
// with CORE algebraic numbers), without clipping. Slow and fragile: a cross-check for small
// scenes and the benchmark, never part of rendering. Throws std::runtime_error if CGAL fails.
struct ExactTopology {
  long vertices = 0, edges = 0, faces = 0;
  double ms = 0;
};
ExactTopology exact_bezier_topology(const std::vector<Wisp>& wisps);

// CGAL's aggregated sweep over the exact kernel (Epeck), unsnapped (a SegmentArrangement): the
// reference our arrangement is tested and benchmarked against. In wisp_vector_exact, like the
// above.
PlanarMap arrange_segments_cgal(const std::vector<OutlineSegment>& segments);

}  // namespace wisp::vector
