// Wisps that can be left out of the arrangement before the sweep: those hidden everywhere by other
// wisps, proved on a coarse grid of squares. Four fifths of the sweep's intersections lie between
// outline pieces nobody sees (docs/performance.md, "The sweep"); a wisp that is never the
// front-most wisp of a face has no visible outline and is no face's front, so its outline need
// not be swept. The test is conservative: it may keep a hidden wisp, never drops one that could be
// any face's front (vector/hidden_wisps.cpp says why, and what of the outputs may still move).
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "vector/planar_map.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

struct HiddenWispOptions {
  double square_px = 4;  // side of the grid's squares (grown when the segments span a huge box)
  // Per occluder (segments with id wisps.size() + k): an upper bound of its depth over a box,
  // +infinity where unknown (Occluder::max_depth); an occluder without one hides nothing here.
  std::vector<std::function<double(const Eigen::AlignedBox2d&)>> occluder_max_depth;
};

struct HiddenParts {
  std::vector<char> wisps;  // per wisp, 1 where it can be left out of the sweep
  // Per wisp with segments, per cell (sections i and i + 1): 1 where something covering every
  // square the cell's box meets is nearer than all of the cell (every cell of a hidden wisp). No
  // face's front can then be the wisp inside the cell, so no depth seam of it can matter
  // (vector/depth_seams.hpp), and the cell can be left out of the sweep
  // (ArrangementOptions::cut_hidden): of whatever covers a square, the nearest has no hidden cell
  // meeting it, so it still covers the square when every hidden cell is left out.
  std::vector<std::vector<char>> cells;
};

// A wisp can be left out where every square its outline or inside may reach is wholly covered by
// another wisp or an occluder that is nearer the eye than it all over the square. `segments` are
// the arrangement's input (vector/planar_map.hpp); wisps with no segment get 0 and no cells.
HiddenParts hidden_wisps(const std::vector<Wisp>& wisps,
                         const std::vector<OutlineSegment>& segments,
                         const HiddenWispOptions& options);

}  // namespace wisp::vector
