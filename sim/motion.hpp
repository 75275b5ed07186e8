// Keyframed head motion. A motion is a list of keyframes (time, position, yaw/pitch/roll) played
// back with cubic Hermite interpolation and Catmull-Rom tangents (zero at the first and last key),
// so the pose and its velocity are continuous (C1): the roots never get an impulse. The presets
// (turn, nod, shake, walk) are generated keyframe lists repeated over the requested duration.
#pragma once

#include <vector>

#include "sim/head.hpp"
#include "sim/params.hpp"

namespace wisp::sim {

// The keyframes of a motion: the preset expanded over motion.duration, or motion.keys.
// Throws std::invalid_argument for bad parameters (validate(MotionParams), as "motion.speed: ...").
std::vector<Keyframe> motion_keys(const MotionParams& motion);

// Rotation of yaw (about y), pitch (about x) and roll (about z), in degrees: R = Ry Rx Rz.
Eigen::Quaterniond rotation_from_ypr(const Eigen::Vector3d& ypr_deg);

class HeadMotion {
 public:
  explicit HeadMotion(std::vector<Keyframe> keys);
  explicit HeadMotion(const MotionParams& motion) : HeadMotion(motion_keys(motion)) {}

  HeadPose pose(double t) const;
  const std::vector<Keyframe>& keys() const { return keys_; }

 private:
  std::vector<Keyframe> keys_;
  std::vector<Eigen::Vector3d> dpos_, dypr_;  // Hermite tangents per key (per second)
};

}  // namespace wisp::sim
