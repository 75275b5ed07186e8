// The parameters of the physical half of a scene: head, hair model, head motion, simulator and
// camera. Plain structs with documented defaults (docs/scene.md lists every field with its unit);
// io/scene_json.cpp fills them from the scene JSON and validates them, sim/ consumes them.
//
// Units: metres, seconds, kilograms; angles given by users are in degrees. Head-local frame: x to
// the viewer's right when the head faces the camera, y up, z forward (out of the face). The
// default camera looks at the face from +z.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wisp::sim {

struct HeadParams {
  std::string shape = "ellipsoid";             // "ellipsoid" or "mesh"
  Eigen::Vector3d radii{0.078, 0.105, 0.095};  // ellipsoid semi-axes along x, y, z (m)
  std::filesystem::path mesh;                  // OBJ file for shape "mesh" (absolute once loaded)
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

struct HairParams {
  std::string source = "procedural";  // "procedural", "json" (our strand format) or "hair" (Yuksel)
  std::filesystem::path file;         // strand file for sources "json" and "hair"
  int count = 150;                    // guides (for files: guides selected from the file, 0 = all)
  int segments = 24;                  // segments per guide (for files: 0 keeps the file's points)
  double length = 0.30;               // mean strand length (m)
  double length_variation = 0.15;     // relative, uniform in [-v, +v]
  std::string style = "wavy";         // "straight", "wavy" or "curly"
  double amplitude = 0.012;           // wave amplitude or curl radius (m)
  double frequency = 8.0;             // waves or curl turns per metre of strand
  double parting_deg = 0.0;           // azimuth of the parting line from the centre (+ = to +x)
  double comb = 1.0;                  // how quickly strands turn from the scalp normal to gravity
  double scalp_angle_deg = 105.0;     // roots lie within this angle of the crown (+y)
  double face_angle_deg = 62.0;       // and farther than this angle from the face direction (+z)
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

struct MotionParams {
  std::string preset = "turn";  // "none", "turn", "nod", "shake", "walk" or "keys"
  double duration = 4.0;        // simulated seconds
  double amplitude = 1.0;       // scales the preset's angles and offsets
  double speed = 1.0;           // scales the preset's tempo
  double settle = 0.5;          // seconds the head holds still before the motion starts
  std::vector<Keyframe> keys;   // preset "keys": user keyframes, increasing times
};

struct WindParams {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // mean wind (m/s, world)
  double gust = 0.0;            // gust speed amplitude along the wind direction (m/s)
  double gust_frequency = 0.5;  // Hz
  std::uint64_t seed = 7;
};

struct SimParams {
  std::string model = "dftl";  // "dftl" (default), "featherstone" (btMultiBody), "rope" (soft body)
  double fps = 24.0;           // saved frames per second
  double step_rate = 120.0;    // fixed physics steps per second
  int substeps = 4;            // sub-steps per physics step
  int iterations = 1;          // constraint iterations per sub-step (dftl, rope)
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
};

}  // namespace wisp::sim
