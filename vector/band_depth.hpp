// Depth inside a wisp. A wisp's depth is known on its centre curve (Faraj 2009, section 3.2.1:
// distance to the eye per sample, linear in between); a point of the band takes the depth of the
// cross-section it lies on. On the flattened band: each cell (the quadrilateral between two
// consecutive sections) is cut along a diagonal into two triangles, and the depth is linear over
// each triangle from the sections' depths at its corners. So the depth is continuous over the
// band and affine in each triangle: where two wisps have equal depth is a line in each pair of
// their triangles, and those lines join up across the triangles' edges (vector/depth_seams.hpp).
// Where a curl overlaps itself several cells contain the point; the nearest one is in front.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <vector>

#include "vector/wisp.hpp"

namespace wisp::vector {

// One of a cell's two triangles: corners and their depths, and the depth as the affine map
// depth(p) = grad . p + offset.
struct CellTriangle {
  std::array<Eigen::Vector2d, 3> v;
  std::array<double, 3> z;
  std::array<int, 3>
      point{};  // which section point each corner is: 2 * section + (0 left, 1 right)
  Eigen::Vector2d grad{0, 0};
  double offset = 0;
  double depth(const Eigen::Vector2d& p) const { return grad.dot(p) + offset; }
};

// Cell i of the wisp (sections i and i + 1) cut along the diagonal that lies inside it; false
// where the cell has no area (a tapered root or tip, a zero-length cell).
bool cell_triangles(const Wisp& wisp, int i, std::array<CellTriangle, 2>& out);

struct BandHit {
  double depth = 0;
  double t = 0;  // centre parameter of the cross-section
};

// A wisp's cells with their bounding boxes, for many lookups in one wisp (the arrangement asks
// once per face and wisp covering it). The boxes are binned into slabs across the wisp's longer
// axis, so a lookup tests only the cells whose box reaches the point's slab, in index order: the
// same cells contain the point as in a scan of all of them, so the answer is the same.
struct BandCells {
  std::vector<std::array<Eigen::Vector2d, 4>> quads;   // left_i, left_i+1, right_i+1, right_i
  std::vector<std::array<CellTriangle, 2>> triangles;  // the depth over each quad
  std::vector<Eigen::AlignedBox2d> boxes;
  int axis = 0;  // 0: slabs along x, 1: along y
  int slabs = 1;
  double slab_min = 0, slab_scale = 0;  // slab of coordinate c: (c - slab_min) * slab_scale
  std::vector<int> slab_begin;          // slab k's cells: slab_cells[slab_begin[k] .. [k + 1])
  std::vector<int> slab_cells;
  int slab_of(double c) const;
};
BandCells band_cells(const Wisp& wisp);

// The front-most cell containing p (on its boundary counts) or, when none does (p a rounding
// error outside the band), the nearest cell.
BandHit band_depth(const Wisp& wisp, const BandCells& cells, const Eigen::Vector2d& p);
BandHit band_depth(const Wisp& wisp, const Eigen::Vector2d& p);

// The front-most cell that contains p at least `margin` px inside its boundary, if any. Used to
// ask whether another pass of a curl covers a point of the wisp's own outline: the point's own
// pass has it on its boundary, so the margin leaves that pass out.
std::optional<BandHit> band_depth_inside(const Wisp& wisp, const BandCells& cells,
                                         const Eigen::Vector2d& p, double margin);
std::optional<BandHit> band_depth_inside(const Wisp& wisp, const Eigen::Vector2d& p, double margin);

}  // namespace wisp::vector
