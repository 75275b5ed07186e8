// Private to vector/: the CGAL types of the wisp arrangement, chosen once. Only
// vector/arrangement_cgal.cpp includes this header (CGAL is slow to compile; nothing else in wisp
// sees it).
//
// Why these types: outlines are flattened into segments, and Arr_segment_traits_2 over Epeck
// (exact predicates and exact constructions: interval filters with lazy exact fallback) keeps
// every intersection point exact, so tangent, coincident and nearly tangent outlines produce a
// valid arrangement with no epsilon anywhere. Measured on this machine, the exact Bezier traits
// (CORE algebraic numbers) cost 85-170x more and have open robustness bugs (prior-work.md D).
// Each segment carries the index of its OutlineSegment; where segments overlap, the indices are
// merged into one edge (a small inline vector: two sources need no allocation). The extended DCEL
// holds an index on every vertex, halfedge and face for the export to PlanarMap.
#pragma once

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
// GCC 12 reports a false -Wstringop-overread inside small_vector's copy.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overread"
#include <boost/container/small_vector.hpp>
#pragma GCC diagnostic pop

namespace wisp::vector::cgal {

using Kernel = CGAL::Epeck;
using Point = Kernel::Point_2;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
using SourceList = boost::container::small_vector<int, 2>;

// Union of the sources of two overlapping pieces, sorted (order-independent, so deterministic).
struct MergeSources {
  SourceList operator()(const SourceList& a, const SourceList& b) const {
    SourceList out(a);
    for (int s : b)
      if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
    std::sort(out.begin(), out.end());
    return out;
  }
};
struct ToSources {
  SourceList operator()(int segment) const { return SourceList{segment}; }
};

using Traits =
    CGAL::Arr_curve_data_traits_2<SegmentTraits, SourceList, MergeSources, int, ToSources>;
using Dcel = CGAL::Arr_extended_dcel<Traits, int, int, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;

}  // namespace wisp::vector::cgal
