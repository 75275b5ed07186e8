// The faces, edges and vertices of a wisp arrangement as plain geometry in pixels (no CGAL): what
// curves inside wisps are clipped to (vector/visible_region.hpp) and what the inspector draws.
// Faces are polygons with holes and know which wisps cover them and which one is in front; edges
// know the outline pieces they come from and whether each is visible; vertices mark the
// intersections. Filled by build_arrangement when ArrangementOptions::keep_faces is set. Indices
// (face_left, face_right, ...) refer to the vectors of the same view.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "vector/wisp.hpp"

namespace wisp::vector {

struct ViewFace {
  std::vector<Eigen::Vector2d> outer;               // empty for the unbounded face
  std::vector<std::vector<Eigen::Vector2d>> holes;  // inner boundaries
  std::vector<std::pair<int, int>> cover;           // (wisp, winding number), winding != 0
  int front = -1;     // front-most wisp; -1 where no wisp covers the face or an occluder is nearer
  bool base = false;  // the hair base is front-most (front is -1 then, but the face is hair)
  double front_depth = 0;        // its depth at `sample`
  Eigen::Vector2d sample{0, 0};  // interior point where the depth order was decided
  bool in_view = false;          // inside the view frame (always true without clipping)
  bool unbounded = false;
};

// One outline piece along an edge. Outline parameters s0 -> s1 follow the edge from `a` to `b`.
struct ViewEdgeSource {
  int wisp = -1;  // -1: a side of the view frame, the hair base or a depth seam; -2 - k: occluder k
  Side side = Side::Left;
  double s0 = 0, s1 = 0;
  bool visible = false;
  bool base = false;  // a piece of the hair base's boundary (s0, s1 on its path)
  bool seam = false;  // a depth seam (vector/depth_seams.hpp): two wisps, or a wisp and an
                      // occluder, swap depth order here
  bool cut = false;   // a line across the wisp's band, beyond which its hidden cells were left out
};

struct ViewEdge {
  Eigen::Vector2d a, b;
  int face_left = -1, face_right = -1;  // faces to the left / right of a -> b (x right, y up)
  std::vector<ViewEdgeSource> sources;
  bool silhouette = false;  // between hair and no hair
  bool occlusion = false;   // between two covered faces with different front-most wisps
};

struct ViewVertex {
  Eigen::Vector2d p;
  int degree = 0;
  bool intersection = false;  // where outlines cross or touch (not a plain polyline joint)
};

struct ArrangementView {
  std::vector<ViewFace> faces;
  std::vector<ViewEdge> edges;
  std::vector<ViewVertex> vertices;
};

}  // namespace wisp::vector
