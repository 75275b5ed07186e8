// Depth seams: the lines inside the hair where two overlapping wisps swap depth order. A wisp's
// depth is affine over each triangle of its band (vector/band_depth.hpp), so where triangles of two
// wisps overlap and their depth ranges meet, the points of equal depth are one line, clipped to
// both triangles; the pieces join up across the triangles' edges. Added to the arrangement's
// input, these segments split every face along which its covering wisps change order, so the one
// depth sample per face that the resolver takes decides the whole face, however the outlines
// around it happen to subdivide the hair (docs/vector.md section 7).
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "vector/arrangement.hpp"
#include "vector/planar_map.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

// The seams between the wisps with `used[w]` set, as segments with wisp id `seam_id`. Left out:
// triangles wholly outside `view` (an empty box: none), and the cells with hidden[w][i] set
// (an empty vector: none; vector/hidden_wisps.hpp). Pairs of triangles are found on a uniform
// grid; the output's order depends only on the input.
//
// Then the seams between the same triangles and the occluders (none: none), where a wisp passes
// behind the head or the body. An occluder's depth is a ray cast, not affine, so over each
// triangle that meets its ring the difference of the two depths is taken as the affine map
// through its values at the three corners (one ray a corner, shared by the triangles around it),
// and the seam piece is that map's zero line. A corner where the ray misses (the occluder's ring
// is a convex hull) counts as the wisp in front; on an edge from there to a corner where the wisp
// is behind, the change is the occluder's silhouette, found by bisection. The pieces join up like
// the wisps' seams; where the occluder's surface bends or folds inside a triangle, or its
// silhouette dips into a triangle whose corners all miss, the seam is off the true change, and
// the face it bounds is still decided at its own sample point with the true depths.
std::vector<OutlineSegment> depth_seams(const std::vector<Wisp>& wisps,
                                        const std::vector<char>& used,
                                        const std::vector<std::vector<char>>& hidden,
                                        const std::vector<Occluder>& occluders, int seam_id,
                                        const Eigen::AlignedBox2d& view);

}  // namespace wisp::vector
