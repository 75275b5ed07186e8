// The parameters of the physical half of a scene: head, hair model, head motion, simulator and
// camera. Plain structs with documented defaults (docs/scene.md lists every field with its unit)
// and one validate() each; io/scene_json.cpp fills them from the scene JSON and validates them,
// sim/ validates what it is given again and consumes it.
//
// Units: metres, seconds, kilograms; angles given by users are in degrees. Head-local frame: x to
// the viewer's right when the head faces the camera, y up, z forward (out of the face). The
// default camera looks at the face from +z.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/choices.hpp"

namespace wisp::sim {

// The head's surface: an analytic ellipsoid or a closed triangle mesh. The values are the head
// codes of .wsim files (io/anim_file.hpp).
enum class HeadKind : std::uint32_t { Ellipsoid = 0, Mesh = 1 };
constexpr std::array<Choice<HeadKind>, 2> choices(HeadKind) {
  return {{{"ellipsoid", HeadKind::Ellipsoid}, {"mesh", HeadKind::Mesh}}};
}

struct HeadParams {
  HeadKind shape = HeadKind::Ellipsoid;
  Eigen::Vector3d radii{0.078, 0.105, 0.095};  // ellipsoid semi-axes along x, y, z (m)
  std::filesystem::path mesh;                  // OBJ file for shape Mesh (absolute once loaded)
  double mesh_scale = 1.0;                     // OBJ units to metres
  Eigen::Vector3d mesh_offset = Eigen::Vector3d::Zero();  // added after scaling (m)
  bool shoulders = false;  // strands also collide with the body: neck, torso and upper arms
  // The figure under the head (sim/body.hpp), in the body frame: the head's position turned by
  // `torso_turn` of its yaw.
  Eigen::Vector3d shoulder_center{0.0, -0.25, -0.02};  // middle of the shoulder line (m)
  double shoulder_half_width = 0.16;  // from there to each shoulder joint, along x (m)
  double shoulder_radius = 0.07;      // half depth of the shoulders (m); scales depths and arms
  double torso_turn = 0.35;           // the torso's share of the head's yaw, in [0, 1]
};

// Where guides come from: generated, or read from our JSON strand format or a Yuksel .hair file.
enum class HairSource { Procedural, Json, Hair };
constexpr std::array<Choice<HairSource>, 3> choices(HairSource) {
  return {{{"procedural", HairSource::Procedural},
           {"json", HairSource::Json},
           {"hair", HairSource::Hair}}};
}

// The offsets of procedural strands: none, a planar wave or a helix.
enum class HairCurl { Straight, Wavy, Curly };
constexpr std::array<Choice<HairCurl>, 3> choices(HairCurl) {
  return {{{"straight", HairCurl::Straight}, {"wavy", HairCurl::Wavy}, {"curly", HairCurl::Curly}}};
}

struct HairParams {
  HairSource source = HairSource::Procedural;
  std::filesystem::path file;  // strand file for sources Json and Hair
  int count = 150;             // guides (for files: guides selected from the file, 0 = all)
  // > 0: the model is dense; its strands (`count` procedural ones, or every strand of a file) are
  // clustered into this many clumps, one guide per clump (sim/clumps.hpp), each as wide as its
  // clump. 0: every strand is a guide and wisps take the style's width.
  int guides = 0;
  int segments = 24;               // segments per guide (for files: 0 keeps the file's points)
  double length = 0.30;            // mean strand length (m)
  double length_variation = 0.15;  // relative, uniform in [-v, +v]
  HairCurl style = HairCurl::Wavy;
  double amplitude = 0.012;        // wave amplitude or curl radius (m)
  double frequency = 8.0;          // waves or curl turns per metre of strand
  double parting_deg = 0.0;        // azimuth of the parting line from the centre (+ = to +x)
  double comb = 1.0;               // how quickly strands turn from the scalp normal to gravity
  double scalp_angle_deg = 105.0;  // roots lie within this angle of the crown (+y)
  double face_angle_deg = 62.0;    // and farther than this angle from the face direction (+z)
  std::uint64_t seed = 1;
  // For file sources: file coordinates to head-local metres.
  double file_scale = 1.0;
  Eigen::Vector3d file_offset = Eigen::Vector3d::Zero();
  bool file_z_up = false;  // the file uses z up (Yuksel's models do): rotate to y up
};

// A head pose keyframe: position (m) and yaw (about y), pitch (about x), roll (about z) in degrees.
struct Keyframe {
  double time = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d ypr_deg = Eigen::Vector3d::Zero();
};

// A generated head motion (sim/motion.cpp), none, or the user's keyframes (Keys).
enum class MotionPreset { None, Turn, Nod, Shake, Walk, Keys };
constexpr std::array<Choice<MotionPreset>, 6> choices(MotionPreset) {
  return {{{"none", MotionPreset::None},
           {"turn", MotionPreset::Turn},
           {"nod", MotionPreset::Nod},
           {"shake", MotionPreset::Shake},
           {"walk", MotionPreset::Walk},
           {"keys", MotionPreset::Keys}}};
}

struct MotionParams {
  MotionPreset preset = MotionPreset::Turn;
  double duration = 4.0;       // simulated seconds
  double amplitude = 1.0;      // scales the preset's angles and offsets
  double speed = 1.0;          // scales the preset's tempo
  double settle = 0.5;         // seconds the head holds still before the motion starts
  std::vector<Keyframe> keys;  // preset Keys: user keyframes, increasing times
};

struct WindParams {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // mean wind (m/s, world)
  double gust = 0.0;            // gust speed amplitude along the wind direction (m/s)
  double gust_frequency = 0.5;  // Hz
  std::uint64_t seed = 7;
};

// The strand solver (sim/solver.hpp): DFTL (the default), Featherstone chains (btMultiBody) or
// Bullet soft-body ropes.
enum class SimModel { Dftl, Featherstone, Rope };
constexpr std::array<Choice<SimModel>, 3> choices(SimModel) {
  return {{{"dftl", SimModel::Dftl},
           {"featherstone", SimModel::Featherstone},
           {"rope", SimModel::Rope}}};
}

struct SimParams {
  SimModel model = SimModel::Dftl;
  double fps = 24.0;                         // saved frames per second
  double step_rate = 120.0;                  // fixed physics steps per second
  int substeps = 4;                          // sub-steps per physics step
  int iterations = 1;                        // constraint iterations per sub-step (dftl, rope)
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2, world
  double density = 0.004;                    // mass per metre of guide strand (kg/m)
  double bend_stiffness = 4e-5;              // bending rigidity towards the rest shape (N m^2)
  double root_stiffness = 4.0;  // bending stiffness at the root, times bend_stiffness (0 = pivot)
  double damping = 2.0;         // internal damping of relative motion (1/s)
  double air_drag = 0.8;        // drag towards the wind velocity (1/s)
  bool collision = true;        // strands collide with the head (and shoulders)
  double collision_margin = 0.003;  // strands keep this far from the head surface (m)
  double max_speed = 60.0;          // a sample faster than this means the integrator blew up (m/s)
  double preroll = 0.0;  // seconds simulated before frame 0, the head held at its first pose
  WindParams wind;
};

// The default light: from the upper front left (world; the head faces +z, x to the viewer's
// right), unit length. Used when a scene has no `light` part.
inline Eigen::Vector3d default_light_dir() {
  return Eigen::Vector3d(-0.45, 0.6, 0.66).normalized();
}

struct CameraParams {
  Eigen::Vector3d eye{0.0, 0.0, 1.1};
  Eigen::Vector3d target{0.0, -0.06, 0.0};
  Eigen::Vector3d up{0.0, 1.0, 0.0};
  double fov_deg = 36.0;  // vertical field of view
  int width = 800;
  int height = 800;
  double hysteresis = 0.004;  // occlusion hysteresis band (m): see sim/camera.hpp
  // Depth of field (vector/hair_blur.hpp): a thin lens with an aperture of this diameter (m),
  // focused on the plane `focus_distance` (m) in front of the eye; 0: the target's distance.
  // Aperture 0: a pinhole, everything sharp.
  double focus_distance = 0;
  double aperture = 0;
};

// Each validate() throws std::invalid_argument("field: what") for the first field out of its
// range, non-finite, or inconsistent with another ("count: must be >= 0 (0 = all strands), got
// -1"). Whoever reads the struct from somewhere puts the place in front: io/ the file and the part
// ("scene.json: hair.count: ..."), sim's entry points the part (validate_part).
void validate(const HeadParams& head);
void validate(const HairParams& hair);
void validate(const std::vector<Keyframe>& keys);  // a motion's keys: "keys[2].time: ..."
void validate(const MotionParams& motion);
void validate(const WindParams& wind);
void validate(const SimParams& sim);
void validate(const CameraParams& camera);

// Budgets: the largest simulation a scene may ask for, checked before anything is allocated
// (docs/scene.md gives the time and memory measured at these limits).
constexpr double kMaxWorldMetres = 100;     // every position, from the head's centre
constexpr double kMaxGuideSamples = 1e6;    // guides x samples per guide
constexpr double kMaxSimWork = 2e8;         // guide samples x sub-steps x iterations
constexpr double kMaxAnimationBytes = 2e9;  // frames x guide samples x 24 bytes, in memory
constexpr int kMaxCameraSide = 16384;       // io::kMaxImageSide
constexpr double kMaxGroomSamples = 2e7;    // strands x samples of a dense procedural model

// The simulation's size against the budgets above: `samples` guide samples in all (guides x
// (segments + 1) for procedural hair, the strands actually kept for files). Throws
// std::invalid_argument("field: what") naming the parameters to lower.
void check_budget(double samples, const MotionParams& motion, const SimParams& sim);

// The building block of every validate(): throws std::invalid_argument("field: what") unless ok.
inline void require(bool ok, const std::string& field, const std::string& what) {
  if (!ok) throw std::invalid_argument(field + ": " + what);
}

// validate(params), with `part` before the field in the message: "hair.count: ...".
template <class Params>
void validate_part(const Params& params, const std::string& part) {
  try {
    validate(params);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(part + "." + e.what());
  }
}

}  // namespace wisp::sim
