// Dense grooms to guides: the strands of a hair model (tens of thousands in a scanned or groomed
// model) clustered into clumps, one guide per clump, and the width of the wisp that stands for
// each clump.
//
// Clustering is k-medoids on a few points per strand: each strand is described by F points at
// equal arc-length fractions (root first), and two strands are as far apart as
// root_weight |a_0 - b_0|^2 + sum_{k>0} |a_k - b_k|^2, so clumps gather strands that grow from
// one patch of scalp and follow one path. Seeds are drawn by k-means++ (Arthur and Vassilvitskii
// 2007), then a few Lloyd-style rounds alternate assigning each strand to its nearest medoid and
// moving each medoid to the member nearest its clump's mean (Park and Jun 2009's simple
// k-medoids, with the mean instead of a sum over all pairs, so a round is linear in the strands).
// Nearest medoids come from a grid over the roots (sim/point_grid.hpp): the root term bounds the
// distance from below, so the search stays exact while visiting only nearby cells. The guide of
// a clump is its medoid, an actual strand of the model. Same strands and seed, same clumps.
//
// A clump's width along its guide: each member sample's distance to the nearest point of the
// guide, gathered at both ends of that guide segment; the width at a guide sample covers the
// `coverage` quantile of what it gathered (wisps interpolate widths between samples without
// overshoot, so a sample is inside when both ends cover it).
#pragma once

#include <cstdint>
#include <vector>

#include "sim/hair_model.hpp"

namespace wisp::sim {

struct ClumpOptions {
  int count = 150;           // clumps; every strand is its own clump when count >= strands
  std::uint64_t seed = 1;    // the k-means++ draws
  int shape_points = 4;      // F points per strand (root and tip included), >= 2
  double root_weight = 4.0;  // weight of the root term against each shape point's
  int rounds = 8;            // Lloyd rounds at most (they stop when no medoid moves)
};

struct Clumps {
  std::vector<int> guide;     // per clump: the index of its medoid strand
  std::vector<int> clump_of;  // per strand: its clump, in [0, guide.size())
};

// Throws std::invalid_argument for no strands, a strand of fewer than 2 points or bad options.
Clumps cluster_strands(const std::vector<Polyline>& strands, const ClumpOptions& options);

// The full width (m) of a clump at each sample of `guide` (the clump's guide as simulated,
// possibly resampled): twice the `coverage` quantile, in (0, 1], of the member samples' distances
// gathered there, at least `min_width`. `members` index `strands`.
std::vector<double> clump_width(const Polyline& guide, const std::vector<Polyline>& strands,
                                const std::vector<int>& members, double coverage = 0.98,
                                double min_width = 0.002);

}  // namespace wisp::sim
