// The ranges of the scene's physical parameters: see params.hpp. These are the only checks of
// them; the scene reader reports their messages with the file and the part in front.
#include "sim/params.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

namespace wisp::sim {
namespace {

bool positive(double v) {
  return v > 0 && std::isfinite(v);
}
// Finite and at most `max`: huge finite values overflow later, in places that cannot name them.
bool at_most(double v, double max) {
  return std::isfinite(v) && std::abs(v) <= max;
}
bool within_world(const Eigen::Vector3d& v) {
  return v.allFinite() && v.norm() <= kMaxWorldMetres;
}
std::string world() {
  return "must lie within " + std::to_string(int(kMaxWorldMetres)) + " m of the head";
}
std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

void validate(const HeadParams& h) {
  require(h.radii.minCoeff() > 0 && h.radii.allFinite() && h.radii.maxCoeff() <= 10, "radii",
          "every radius must be in (0, 10] m");
  require(h.shape != HeadKind::Mesh || !h.mesh.empty(), "mesh",
          std::string("shape \"") + choice_name(HeadKind::Mesh) + "\" needs an OBJ file name");
  require(positive(h.mesh_scale) && h.mesh_scale <= 1e6, "mesh_scale", "must be in (0, 1e6]");
  require(within_world(h.mesh_offset), "mesh_offset", world());
  require(within_world(h.shoulder_center), "shoulder_center", world());
  require(h.shoulder_half_width >= 0 && h.shoulder_half_width <= 10, "shoulder_half_width",
          "must be in [0, 10] m");
  require(h.shoulder_radius > 0 && h.shoulder_radius <= 10, "shoulder_radius",
          "must be in (0, 10] m");
  require(h.torso_turn >= 0 && h.torso_turn <= 1, "torso_turn", "must be in [0, 1]");
}

void validate(const HairParams& h) {
  // Strand files may keep all their strands (count 0) and their own points (segments 0).
  const bool procedural = h.source == HairSource::Procedural;
  require(procedural || !h.file.empty(), "file",
          std::string("source \"") + choice_name(h.source) + "\" needs a strand file name");
  // Procedural hair may be left out (count 0) on a head that only grows fur (sim/fur.hpp).
  require(h.count >= 0, "count",
          std::string("must be ") + (procedural ? ">= 0 (0 = no hair)" : ">= 0 (0 = all strands)") +
              ", got " + std::to_string(h.count));
  require(h.count <= 100000, "count", "at most 100000 guides");
  require(h.guides >= 0 && h.guides <= 100000, "guides",
          "must be in [0, 100000] (0: every strand is a guide), got " + std::to_string(h.guides));
  require(procedural ? h.segments >= 1 : h.segments >= 0, "segments",
          "must be at least 1 (0 keeps a file's points), got " + std::to_string(h.segments));
  require(h.segments <= 1000, "segments", "at most 1000");
  require(!procedural || h.guides == 0 || double(h.count) * (h.segments + 1) <= kMaxGroomSamples,
          "count", "a dense model (with guides) has at most 2e7 samples: count x (segments + 1)");
  require(positive(h.length) && h.length <= 10, "length", "must be in (0, 10] m");
  require(h.length_variation >= 0 && h.length_variation < 1, "length_variation",
          "must be in [0, 1)");
  require(h.amplitude >= 0 && h.amplitude <= 1, "amplitude", "must be in [0, 1] m");
  require(h.frequency >= 0 && h.frequency <= 1000, "frequency", "must be in [0, 1000] per metre");
  require(at_most(h.parting_deg, 360), "parting_deg", "must be in [-360, 360]");
  require(h.comb >= 0 && h.comb <= 1000, "comb", "must be in [0, 1000]");
  require(h.scalp_angle_deg > 0 && h.scalp_angle_deg <= 180, "scalp_angle_deg",
          "must be in (0, 180]");
  require(h.face_angle_deg >= 0 && h.face_angle_deg < 180, "face_angle_deg", "must be in [0, 180)");
  require(positive(h.file_scale) && h.file_scale <= 1e6, "file_scale", "must be in (0, 1e6]");
  require(within_world(h.file_offset), "file_offset", world());
}

void validate(const std::vector<Keyframe>& keys) {
  require(!keys.empty(), "keys", "at least one keyframe is needed");
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const Keyframe& k = keys[i];
    const std::string at = "keys[" + std::to_string(i) + "]";
    require(k.time >= 0 && k.time <= 3600, at + ".time", "must be in [0, 3600] seconds");
    require(within_world(k.position), at + ".position", world());
    require(k.ypr_deg.allFinite() && k.ypr_deg.cwiseAbs().maxCoeff() <= 3600, at + ".ypr_deg",
            "angles must be in [-3600, 3600] degrees");
    require(i == 0 || k.time > keys[i - 1].time, at + ".time", "keyframe times must increase");
  }
}

void validate(const MotionParams& m) {
  require(m.duration > 0 && m.duration <= 3600, "duration", "must be in (0, 3600] seconds");
  require(at_most(m.amplitude, 100), "amplitude", "must be in [-100, 100]");
  require(positive(m.speed) && m.speed <= 1000, "speed", "must be in (0, 1000]");
  require(m.settle >= 0 && m.settle <= 3600, "settle", "must be in [0, 3600] seconds");
  require(m.preset != MotionPreset::Keys || !m.keys.empty(), "keys",
          std::string("preset \"") + choice_name(MotionPreset::Keys) +
              "\" needs at least one keyframe");
  if (!m.keys.empty()) validate(m.keys);
}

void validate(const WindParams& w) {
  require(w.velocity.allFinite() && w.velocity.norm() <= 1000, "velocity",
          "must be at most 1000 m/s");
  require(w.gust >= 0 && w.gust <= 1000, "gust", "must be in [0, 1000] m/s");
  require(w.gust_frequency >= 0 && w.gust_frequency <= 1000, "gust_frequency",
          "must be in [0, 1000] Hz");
}

void validate(const SimParams& s) {
  require(s.fps > 0 && s.fps <= 1000, "fps", "must be in (0, 1000]");
  require(s.step_rate >= s.fps && s.step_rate <= 100000, "step_rate",
          "must be in [sim.fps, 100000] Hz");
  require(s.substeps >= 1 && s.substeps <= 1000, "substeps", "must be in [1, 1000]");
  require(s.iterations >= 1 && s.iterations <= 1000, "iterations", "must be in [1, 1000]");
  require(s.gravity.allFinite() && s.gravity.norm() <= 1000, "gravity",
          "must be at most 1000 m/s^2");
  require(positive(s.density) && s.density <= 1000, "density", "must be in (0, 1000] kg/m");
  require(s.bend_stiffness >= 0 && s.bend_stiffness <= 1000, "bend_stiffness",
          "must be in [0, 1000] N m^2");
  require(s.root_stiffness >= 0 && s.root_stiffness <= 1e6, "root_stiffness",
          "must be in [0, 1e6]");
  require(s.damping >= 0 && s.damping <= 1e6, "damping", "must be in [0, 1e6] 1/s");
  require(s.air_drag >= 0 && s.air_drag <= 1e6, "air_drag", "must be in [0, 1e6] 1/s");
  require(s.collision_margin >= 0 && s.collision_margin <= 1, "collision_margin",
          "must be in [0, 1] m");
  require(positive(s.max_speed) && s.max_speed <= 1e6, "max_speed", "must be in (0, 1e6] m/s");
  require(s.preroll >= 0 && s.preroll <= 600, "preroll", "must be in [0, 600] seconds");
  validate_part(s.wind, "wind");
}

void validate(const CameraParams& c) {
  require(c.eye.allFinite() && c.eye.norm() <= 10 * kMaxWorldMetres, "eye",
          "must lie within " + std::to_string(int(10 * kMaxWorldMetres)) + " m of the head");
  require(within_world(c.target), "target", world());
  require(c.up.allFinite() && c.up.norm() <= 1e6 && c.up.norm() > 1e-6, "up",
          "must be a vector of length in [1e-6, 1e6]");
  const Eigen::Vector3d view = c.target - c.eye;
  require(view.norm() > 1e-9, "target", "must differ from camera.eye");
  require(view.normalized().cross(c.up).norm() > 1e-9, "up", "must not be parallel to the view");
  require(c.fov_deg > 0 && c.fov_deg < 180, "fov_deg", "must be in (0, 180)");
  const std::string side = "must be in [1, " + std::to_string(kMaxCameraSide) + "] pixels";
  require(c.width >= 1 && c.width <= kMaxCameraSide, "width", side);
  require(c.height >= 1 && c.height <= kMaxCameraSide, "height", side);
  require(c.hysteresis >= 0 && c.hysteresis <= 1, "hysteresis", "must be in [0, 1] m");
  require(c.focus_distance >= 0 && c.focus_distance <= 10 * kMaxWorldMetres, "focus_distance",
          "must be in [0, " + std::to_string(int(10 * kMaxWorldMetres)) +
              "] m (0: the target's distance)");
  require(c.aperture >= 0 && c.aperture <= 1, "aperture",
          "must be in [0, 1] m (the lens's diameter; 0: a pinhole, all in focus)");
}

void check_budget(double samples, const MotionParams& motion, const SimParams& sim) {
  require(samples <= kMaxGuideSamples, "hair.count",
          sci(samples) + " guide samples (hair.count x (hair.segments + 1)) exceed the budget of " +
              sci(kMaxGuideSamples) + "; lower hair.count or hair.segments");
  const double seconds = motion.duration + sim.preroll;
  const double work = samples * std::ceil(seconds * sim.step_rate) * sim.substeps * sim.iterations;
  require(work <= kMaxSimWork, "sim.step_rate",
          sci(work) + " sample updates (guide samples x (motion.duration + sim.preroll) x " +
              "sim.step_rate x sim.substeps x sim.iterations) exceed the budget of " +
              sci(kMaxSimWork) + "; lower one of them");
  const double bytes = samples * (std::floor(motion.duration * sim.fps) + 1) * 24;
  require(bytes <= kMaxAnimationBytes, "sim.fps",
          "the animation would take " + sci(bytes / 1e9) +
              " GB (guide samples x frames x 24 bytes), above " + sci(kMaxAnimationBytes / 1e9) +
              " GB; lower sim.fps, motion.duration or the hair's size");
}

}  // namespace wisp::sim
