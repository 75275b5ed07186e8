// Guide strands at rest, in head-local metres, root first: the procedural generator (blue-noise
// roots on the scalp, gravity-combed growth that drapes over the head, straight / wavy / curly
// offsets), and the tools that turn a dense strand file into guides (farthest-point selection of
// roots spread over the scalp, arc-length resampling).
#pragma once

#include <vector>

#include "sim/head.hpp"
#include "sim/params.hpp"

namespace wisp::sim {

using Polyline = std::vector<Eigen::Vector3d>;

// Generates hair.count procedural guides of hair.segments segments, every point but the root at
// least `clearance` from the head. Deterministic in hair.seed. Throws std::invalid_argument for
// bad parameters (non-positive counts, lengths...).
std::vector<Polyline> generate_hair(const HairParams& hair, const HeadShape& head,
                                    double clearance = 0.005);

// Picks `count` strands whose roots are spread evenly (greedy farthest-point sampling starting at
// the strand whose root is highest). Returns indices into `strands`, in selection order.
std::vector<int> select_guides(const std::vector<Polyline>& strands, int count);

// Resamples a polyline to `segments` pieces of equal arc length (ends kept).
Polyline resample(const Polyline& strand, int segments);

// Moves the non-root points of a rest strand out of the head (and shoulders), to at least
// `clearance` from the surface, so the simulation does not start with a collision.
void clear_head(Polyline& strand, const HeadShape& head, double clearance);

// Mean distance of each sample from the midpoint of the samples `half` before and after it,
// halved: the radius for a helix when `half` covers half a turn, 0 for a straight strand.
double curl_amplitude(const Polyline& strand, int half);

}  // namespace wisp::sim
