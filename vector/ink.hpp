// Private to vector/: outlines traced on the resolved planar map. The hair mask is the boundary of
// the union of hair faces, walked as closed cycles and grouped per connected hair region (outer
// boundary plus holes), and so are the regions where each wisp is in front; the silhouette and
// occlusion boundaries are chains of selected edges, broken where more than two meet or where the
// wisp that owns the ink changes.
#pragma once

#include <vector>

#include "vector/arrangement.hpp"
#include "vector/planar_map.hpp"

namespace wisp::vector {

// The regions of faces with equal labels, one HairMask per label 0 .. labels-1: label[f] >= 0 is
// face f's label, -1 leaves it out. Boundaries run between faces of different labels.
std::vector<HairMask> trace_regions(const PlanarMap& map, const std::vector<int>& label,
                                    int labels);

// hair[f]: face f is covered and inside the view.
HairMask trace_hair_mask(const PlanarMap& map, const std::vector<char>& hair);

// Chains the edges with owner[e] >= 0 into polylines; consecutive edges of a chain share a vertex
// where exactly two selected edges meet, both with the same owner (which becomes InkLine::wisp).
std::vector<InkLine> chain_edges(const PlanarMap& map, const std::vector<int>& owner);

}  // namespace wisp::vector
