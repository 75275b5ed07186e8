// Fur: short dense hair on the head (Sheppard 2004, ../shared/research/seed-001.md), as thousands
// of tufts, each a clump of a few strands a centimetre or so long. Sheppard drew fur as shells
// (the coat's colour) and fins (strips standing on edges near the silhouette, fading in with
// N.V); in our 2D pipeline the shells become the hair base (the shaded region under the hair,
// sim/scalp.hpp, vector/hair_base.hpp) and the fins become tufts drawn where the surface turns
// away from the eye (vector/fur.hpp).
//
// Roots: a Fibonacci lattice of directions from the head's centre, jittered by the seed, kept
// inside the fur's region (within `scalp_angle_deg` of the crown and farther than
// `face_angle_deg` from the face, as the hair's scalp), each projected onto the head.
// Direction: the surface normal combed towards a head-local direction field (the tangential part
// of `comb_direction`) by `comb`, which is the tangent of the lean: 0 stands up, 1 leans 45 deg.
//
// Motion: one damped spring per tuft, not the strand simulation. A tuft is short and stiff, so it
// hardly bends along its length: its state is one tip point, pulled towards its combed rest tip
// (which moves with the head) by `stiffness`, damped relative to the root by `damping`, pushed by
// gravity and by the wind through `drag`, then put back at the tuft's length from the root and
// kept off the skin. The head's motion drives it through the inertia of the tip: when the head
// turns, the rest tip moves and the tip lags and overshoots. This costs a few vector operations per
// tuft per step (thousands of tufts for every frame in milliseconds), where the strand solvers cost
// a collision-checked chain per strand; it is Delta-t correct (a fixed step, sub-stepped between
// frames), which Sheppard's force blend was not. The shape of a strand is Sheppard's bend: a
// quadratic Bezier from the root through half the rest direction's length to the tip.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/camera.hpp"
#include "sim/head.hpp"
#include "sim/params.hpp"

namespace wisp::sim {

struct FurParams {
  int count = 0;                  // tufts over the fur's region (about); 0: no fur
  double length = 0.012;          // mean tuft length (m)
  double length_variation = 0.3;  // relative, uniform in [-v, +v], per tuft and per strand
  int strands = 5;                // strands per tuft
  double clump_radius = 0.6;      // strands' roots spread this far, in tuft spacings
  double clump = 0.6;             // 0: strands parallel, 1: their tips meet at the tuft's tip
  double scalp_angle_deg = 180;   // region: within this angle of the crown (+y)
  double face_angle_deg = 0;      // and farther than this from the face direction (+z)
  Eigen::Vector3d comb_direction{0, -0.4, -1};  // head-local; its tangential part combs the fur
  double comb = 1.2;                            // tangent of the lean towards the comb direction
  double stiffness = 2500;  // spring (1/s^2): the sag under gravity is g / stiffness
  double damping = 18;      // relative to the root (1/s)
  double drag = 8;          // towards the wind (1/s)
  double step_rate = 480;   // spring steps per second
  std::uint64_t seed = 3;
};

// Throws std::invalid_argument("field: what") for a field out of range.
void validate(const FurParams& fur);

// Does fur grow in head-local direction `d` (unit, from the head's centre)?
bool in_fur_region(const Eigen::Vector3d& d, const FurParams& fur);

// The combed rest direction of fur on skin of unit normal n (head-local): n leaned towards the
// comb direction's tangential part by `comb`.
Eigen::Vector3d fur_direction(const Eigen::Vector3d& n, const FurParams& fur);

struct FurStrand {
  Eigen::Vector3d root_offset = Eigen::Vector3d::Zero();  // from the tuft's root, head-local
  Eigen::Vector3d tip_offset = Eigen::Vector3d::Zero();   // added to the tuft's tip, head-local
  double length_scale = 1;
};

struct FurTuftRest {
  Eigen::Vector3d root, normal, direction;  // head-local: root on the head, unit vectors
  double length = 0;
  double variance = 1;  // Sheppard's per-hair colour variance, a factor in [0.8, 1]
  std::vector<FurStrand> strands;
};

struct FurModel {
  std::vector<FurTuftRest> tufts;
  double spacing = 0;  // mean distance between neighbouring roots (m)
};

// Deterministic in fur.seed. Empty for count 0.
FurModel make_fur(const FurParams& fur, const HeadShape& head);

// The tips of every tuft at each time, world space, from the head's motion and the wind.
struct FurMotion {
  std::vector<std::vector<Eigen::Vector3d>> tips;  // [frame][tuft]
};

class Environment;
// `times`: increasing frame times (s); the springs start at rest at the first, settled under
// gravity and wind for `settle` seconds of the first pose.
FurMotion simulate_fur(const FurModel& model, const FurParams& fur, const Environment& env,
                       const std::vector<double>& times, double settle = 0.5);

// One tuft as the camera sees it (the fur's counterpart of ProjectedStrand).
struct ProjectedTuft {
  int id = 0;         // index into FurModel::tufts
  double depth = 0;   // distance from the eye to the root
  double facing = 0;  // N.V: the surface normal at the root against the unit vector to the eye
  Eigen::Vector3d root, tangent, normal;  // world: root, unit root-to-tip, unit surface normal
  // Per strand: root, control point and tip of its quadratic Bezier, in pixels.
  std::vector<Eigen::Vector2d> strand_points;  // 3 per strand
  std::vector<double> strand_depth;            // distance from the eye to each strand's root
  double variance = 1;                         // FurTuftRest::variance
};

struct ProjectedFur {
  double focal_px = 0;
  Eigen::Vector3d eye = Eigen::Vector3d::Zero(), light_dir = Eigen::Vector3d::UnitZ();
  std::vector<ProjectedTuft> tufts;  // only tufts with |facing| below `max_facing`
};

// The tufts of one frame with |N.V| < max_facing (1 keeps every one in front of the eye).
ProjectedFur project_fur(const FurModel& model, const std::vector<Eigen::Vector3d>& tips,
                         const HeadPose& pose, const Camera& camera,
                         const Eigen::Vector3d& light_dir, double max_facing);

}  // namespace wisp::sim
