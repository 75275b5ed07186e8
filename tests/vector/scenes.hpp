// Test scenes for vector/: hand-made strands (straight, wavy, curly) and seeded random frames of
// many such strands, as the simulation would hand them over (pixel, depth, tangent per sample).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/projected.hpp"

namespace wisp::test {

// A strand sampled from a parametric curve q(u), u in [0,1]: x, y in pixels, z = depth.
sim::ProjectedStrand strand_from(int id, int samples,
                                 const std::function<Eigen::Vector3d(double)>& q);

// Straight strand from a to b (pixels) at depths za -> zb.
sim::ProjectedStrand straight(int id, Eigen::Vector2d a, Eigen::Vector2d b, double za, double zb,
                              int samples = 8);

// A frame of the given size with focal length 800 px holding these strands.
sim::ProjectedFrame frame_of(std::vector<sim::ProjectedStrand> strands, int width = 512,
                             int height = 512);

enum class Kind { Straight, Wavy, Curly };

// `count` strands with seeded random roots, directions, lengths (60-180 px) and depths (2-4),
// a third each straight, wavy (sine, wavelength 30-60 px, amplitude 3-10 px) and curly
// (a helix seen from the side, radius 5-12 px, pitch 25-45 px: some coils loop in projection and
// make the band overlap itself; `loops` false keeps every coil's projection loop-free).
sim::ProjectedFrame random_frame(int count, std::uint32_t seed, int width = 512, int height = 512,
                                 bool loops = true);

}  // namespace wisp::test
