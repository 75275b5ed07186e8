// The ranges of the scene's physical parameters: see params.hpp. These are the only checks of
// them; the scene reader reports their messages with the file and the part in front.
#include "sim/params.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace wisp::sim {
namespace {

bool positive(double v) {
  return v > 0 && std::isfinite(v);
}
bool non_negative(double v) {
  return v >= 0 && std::isfinite(v);
}

}  // namespace

void validate(const HeadParams& h) {
  require(h.radii.minCoeff() > 0 && h.radii.allFinite(), "radii", "every radius must be positive");
  require(h.shape != HeadKind::Mesh || !h.mesh.empty(), "mesh",
          std::string("shape \"") + choice_name(HeadKind::Mesh) + "\" needs an OBJ file name");
  require(positive(h.mesh_scale), "mesh_scale", "must be positive");
  require(h.mesh_offset.allFinite(), "mesh_offset", "not a finite vector");
  require(h.shoulder_center.allFinite(), "shoulder_center", "not a finite vector");
  require(non_negative(h.shoulder_half_width), "shoulder_half_width", "must be >= 0");
  require(positive(h.shoulder_radius), "shoulder_radius", "must be positive");
  require(h.torso_turn >= 0 && h.torso_turn <= 1, "torso_turn", "must be in [0, 1]");
}

void validate(const HairParams& h) {
  // Strand files may keep all their strands (count 0) and their own points (segments 0).
  const bool procedural = h.source == HairSource::Procedural;
  require(procedural || !h.file.empty(), "file",
          std::string("source \"") + choice_name(h.source) + "\" needs a strand file name");
  require(procedural ? h.count >= 1 : h.count >= 0, "count",
          std::string("must be ") + (procedural ? "at least 1" : ">= 0 (0 = all strands)") +
              ", got " + std::to_string(h.count));
  require(h.count <= 100000, "count", "at most 100000 guides");
  require(procedural ? h.segments >= 1 : h.segments >= 0, "segments",
          "must be at least 1 (0 keeps a file's points), got " + std::to_string(h.segments));
  require(h.segments <= 1000, "segments", "at most 1000");
  require(positive(h.length), "length", "must be a positive length in metres");
  require(h.length_variation >= 0 && h.length_variation < 1, "length_variation",
          "must be in [0, 1)");
  require(non_negative(h.amplitude), "amplitude", "must be >= 0");
  require(non_negative(h.frequency), "frequency", "must be >= 0");
  require(std::isfinite(h.parting_deg), "parting_deg", "not a finite number");
  require(non_negative(h.comb), "comb", "must be >= 0");
  require(h.scalp_angle_deg > 0 && h.scalp_angle_deg <= 180, "scalp_angle_deg",
          "must be in (0, 180]");
  require(h.face_angle_deg >= 0 && h.face_angle_deg < 180, "face_angle_deg", "must be in [0, 180)");
  require(positive(h.file_scale), "file_scale", "must be positive");
  require(h.file_offset.allFinite(), "file_offset", "not a finite vector");
}

void validate(const std::vector<Keyframe>& keys) {
  require(!keys.empty(), "keys", "at least one keyframe is needed");
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const Keyframe& k = keys[i];
    const std::string at = "keys[" + std::to_string(i) + "]";
    require(std::isfinite(k.time) && k.position.allFinite() && k.ypr_deg.allFinite(), at,
            "not a finite number");
    require(i == 0 || k.time > keys[i - 1].time, at + ".time", "keyframe times must increase");
  }
}

void validate(const MotionParams& m) {
  require(m.duration > 0 && m.duration <= 3600, "duration", "must be in (0, 3600] seconds");
  require(std::isfinite(m.amplitude), "amplitude", "not a finite number");
  require(positive(m.speed), "speed", "must be positive");
  require(non_negative(m.settle), "settle", "must be >= 0");
  require(m.preset != MotionPreset::Keys || !m.keys.empty(), "keys",
          std::string("preset \"") + choice_name(MotionPreset::Keys) +
              "\" needs at least one keyframe");
  if (!m.keys.empty()) validate(m.keys);
}

void validate(const WindParams& w) {
  require(w.velocity.allFinite(), "velocity", "not a finite vector");
  require(non_negative(w.gust), "gust", "must be >= 0 (m/s)");
  require(non_negative(w.gust_frequency), "gust_frequency", "must be >= 0 (Hz)");
}

void validate(const SimParams& s) {
  require(s.fps > 0 && s.fps <= 1000, "fps", "must be in (0, 1000]");
  require(s.step_rate >= s.fps && s.step_rate <= 100000, "step_rate",
          "must be in [sim.fps, 100000] Hz");
  require(s.substeps >= 1 && s.substeps <= 1000, "substeps", "must be in [1, 1000]");
  require(s.iterations >= 1 && s.iterations <= 1000, "iterations", "must be in [1, 1000]");
  require(s.gravity.allFinite(), "gravity", "not a finite vector");
  require(positive(s.density), "density", "must be positive (kg/m)");
  require(non_negative(s.bend_stiffness), "bend_stiffness", "must be >= 0 (N m^2)");
  require(non_negative(s.root_stiffness), "root_stiffness", "must be >= 0");
  require(non_negative(s.damping), "damping", "must be >= 0 (1/s)");
  require(non_negative(s.air_drag), "air_drag", "must be >= 0 (1/s)");
  require(non_negative(s.collision_margin), "collision_margin", "must be >= 0 (m)");
  require(positive(s.max_speed), "max_speed", "must be positive (m/s)");
  require(s.preroll >= 0 && s.preroll <= 600, "preroll", "must be in [0, 600] seconds");
  validate_part(s.wind, "wind");
}

void validate(const CameraParams& c) {
  require(c.eye.allFinite(), "eye", "not a finite vector");
  require(c.target.allFinite(), "target", "not a finite vector");
  require(c.up.allFinite(), "up", "not a finite vector");
  const Eigen::Vector3d view = c.target - c.eye;
  require(view.norm() > 1e-9, "target", "must differ from camera.eye");
  require(view.normalized().cross(c.up).norm() > 1e-9, "up", "must not be parallel to the view");
  require(c.fov_deg > 0 && c.fov_deg < 180, "fov_deg", "must be in (0, 180)");
  require(c.width >= 1 && c.width <= 65536, "width", "must be in [1, 65536] pixels");
  require(c.height >= 1 && c.height <= 65536, "height", "must be in [1, 65536] pixels");
  require(non_negative(c.hysteresis), "hysteresis", "must be >= 0 (m)");
}

}  // namespace wisp::sim
