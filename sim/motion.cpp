// HeadMotion and the motion presets: see motion.hpp.
#include "sim/motion.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

// One cycle of a preset: keys over [0, period), repeated. Angles in degrees, offsets in metres.
struct Cycle {
  double period;
  std::vector<Keyframe> keys;
};

// The cycle of a generated preset (not None or Keys, which motion_keys handles itself).
Cycle preset_cycle(MotionPreset preset) {
  const auto key = [](double t, Vector3d pos, Vector3d ypr) { return Keyframe{t, pos, ypr}; };
  const Vector3d o = Vector3d::Zero();
  switch (preset) {
    case MotionPreset::Turn:  // look right, back, left, back
      return {4.0,
              {key(0.0, o, o), key(0.9, o, {65, 0, 0}), key(1.5, o, {65, 0, 0}), key(2.4, o, o),
               key(3.2, o, {-50, 5, 0})}};
    case MotionPreset::Nod:
      return {1.2, {key(0.0, o, o), key(0.45, o, {0, 28, 0}), key(0.9, o, {0, -8, 0})}};
    case MotionPreset::Shake:  // a violent "no": +-40 degrees at about 2.8 Hz
      return {0.36, {key(0.0, o, {-40, 0, 0}), key(0.18, o, {40, 0, 0})}};
    case MotionPreset::Walk:  // bob twice per stride, sway once, a little yaw and roll
      return {1.0,
              {key(0.0, {0.02, 0, 0}, {4, 0, -3}), key(0.25, {0, -0.015, 0}, {0, 2, 0}),
               key(0.5, {-0.02, 0, 0}, {-4, 0, 3}), key(0.75, {0, -0.015, 0}, {0, 2, 0})}};
    case MotionPreset::None:
    case MotionPreset::Keys:
      break;
  }
  throw std::logic_error(std::string("preset_cycle: \"") + choice_name(preset) +
                         "\" is not a generated motion");
}

// Catmull-Rom tangents for non-uniform times; zero at both ends so the motion starts and ends at
// rest.
template <class Get>
std::vector<Vector3d> tangents(const std::vector<Keyframe>& keys, Get get) {
  std::vector<Vector3d> m(keys.size(), Vector3d::Zero());
  for (std::size_t i = 1; i + 1 < keys.size(); ++i)
    m[i] = (get(keys[i + 1]) - get(keys[i - 1])) / (keys[i + 1].time - keys[i - 1].time);
  return m;
}

Vector3d hermite(const Vector3d& p0, const Vector3d& m0, const Vector3d& p1, const Vector3d& m1,
                 double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * p1 +
         (s3 - s2) * h * m1;
}

}  // namespace

std::vector<Keyframe> motion_keys(const MotionParams& motion) {
  validate_part(motion, "motion");
  if (motion.preset == MotionPreset::Keys) return motion.keys;
  std::vector<Keyframe> keys{Keyframe{}};
  if (motion.preset == MotionPreset::None) return keys;
  const Cycle cycle = preset_cycle(motion.preset);
  const double period = cycle.period / motion.speed;
  // Repeat whole cycles past the end, then close on the rest pose.
  double start = motion.settle;
  for (; start < motion.duration; start += period)
    for (const Keyframe& k : cycle.keys) {
      Keyframe out{start + k.time / motion.speed, motion.amplitude * k.position,
                   motion.amplitude * k.ypr_deg};
      if (out.time > keys.back().time) keys.push_back(out);
    }
  keys.push_back(Keyframe{start + 0.5 * period, Vector3d::Zero(), Vector3d::Zero()});
  return keys;
}

Eigen::Quaterniond rotation_from_ypr(const Vector3d& ypr_deg) {
  const Vector3d a = ypr_deg * (M_PI / 180.0);
  return Eigen::Quaterniond(Eigen::AngleAxisd(a[0], Vector3d::UnitY()) *
                            Eigen::AngleAxisd(a[1], Vector3d::UnitX()) *
                            Eigen::AngleAxisd(a[2], Vector3d::UnitZ()));
}

HeadMotion::HeadMotion(std::vector<Keyframe> keys) : keys_(std::move(keys)) {
  validate_part(keys_, "motion");
  dpos_ = tangents(keys_, [](const Keyframe& k) { return k.position; });
  dypr_ = tangents(keys_, [](const Keyframe& k) { return k.ypr_deg; });
}

HeadPose HeadMotion::pose(double t) const {
  Vector3d pos, ypr;
  if (t <= keys_.front().time) {
    pos = keys_.front().position;
    ypr = keys_.front().ypr_deg;
  } else if (t >= keys_.back().time) {
    pos = keys_.back().position;
    ypr = keys_.back().ypr_deg;
  } else {
    std::size_t i = 0;
    while (keys_[i + 1].time <= t) ++i;
    const double h = keys_[i + 1].time - keys_[i].time;
    const double s = (t - keys_[i].time) / h;
    pos = hermite(keys_[i].position, dpos_[i], keys_[i + 1].position, dpos_[i + 1], h, s);
    ypr = hermite(keys_[i].ypr_deg, dypr_[i], keys_[i + 1].ypr_deg, dypr_[i + 1], h, s);
  }
  return HeadPose{pos, rotation_from_ypr(ypr)};
}

}  // namespace wisp::sim
