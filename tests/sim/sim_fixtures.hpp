// Small setups shared by the sim tests: a single strand on a still head, and a few guides of
// procedural hair on a moving one. Kept small so each test runs in well under a second or two.
#pragma once

#include <cmath>

#include "sim/motion.hpp"
#include "sim/simulate.hpp"

namespace wisp::sim::test {

// One straight strand of `length` and `segments` hanging from the origin at `angle_deg` from
// straight down (in the x-y plane), on a still head, no collisions, no drag.
inline SimSetup single_strand(double length, int segments, double angle_deg, double duration) {
  SimSetup s;
  s.motion = {Keyframe{}};
  s.duration = duration;
  const double a = angle_deg * M_PI / 180;
  const Eigen::Vector3d dir(std::sin(a), -std::cos(a), 0);
  Polyline strand;
  for (int i = 0; i <= segments; ++i)
    strand.push_back(Eigen::Vector3d(0, 0.2, 0) + dir * (length * i / segments));
  s.rest = {strand};
  s.sim.collision = false;
  s.sim.air_drag = 0;
  s.sim.damping = 0;
  return s;
}

// `count` procedural guides with the given style on a head doing `preset`.
inline SimSetup small_head(int count, int segments, HairCurl style, MotionPreset preset,
                           double duration) {
  HeadParams head;
  HairParams hair;
  hair.count = count;
  hair.segments = segments;
  hair.style = style;
  MotionParams motion;
  motion.preset = preset;
  motion.duration = duration;
  SimParams sim;
  return make_setup(head, hair, motion, sim);
}

}  // namespace wisp::sim::test
