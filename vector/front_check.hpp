// How well an arrangement's fronts agree with the depths, point by point: random points in the
// covered faces, each decided by the depths there (the covering wisps' band depth, the
// occluders' ray cast) and compared with its face's front. The arrangement decides a face at one
// sample point; the depth seams are what make that decision hold over the whole face
// (vector/depth_seams.hpp). For the tests and `wisp-bench fronts`, not for rendering.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "vector/arrangement.hpp"
#include "vector/arrangement_view.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

struct FrontCheckOptions {
  int points_per_face = 12;
  std::uint32_t seed = 7;
  // Points for which this is true are not counted (e.g. near a line the check is not about).
  std::function<bool(const Eigen::Vector2d&)> skip;
};

struct FrontCheck {
  long faces = 0, points = 0, wrong_points = 0, wrong_faces = 0;
  double covered_area = 0;  // px^2 of the faces checked
  double wrong_area = 0;    // px^2: each face's area times its share of wrong points
};

// Every face that wisps cover, inside the view, gets `points_per_face` uniform points in its box;
// those inside it by more than 1e-3 px are decided: the nearest covering wisp there, unless an
// occluder whose ring holds the point is nearer (then no wisp: front -1). Points where the two
// nearest are within 1e-9 of each other are ties either way and not counted.
FrontCheck check_fronts(const std::vector<Wisp>& wisps, const ArrangementView& view,
                        const std::vector<Occluder>& occluders,
                        const FrontCheckOptions& options = {});

}  // namespace wisp::vector
