// The head and body: the solids the hair collides with and is hidden by, and their surfaces as
// the camera sees them, for the renderer to paint under the hair. Plain data and Eigen only (no
// Bullet); the projection is sim::Camera's, so the body lines up exactly with the
// ProjectedFrames of the hair.
//
// Five solids, each a closed smooth surface:
//  - the head: the HeadGeometry the strands collided with (an ellipsoid tessellated into
//    `slices` x `stacks` and scaled out so the polyhedron just contains the ellipsoid, or the
//    mesh as it is), posed by the frame's HeadPose;
//  - the neck: a sweep (sim/sweep.hpp) from a point inside the shoulders (body frame) to a point
//    inside the head (head-local: it follows the head's turns and nods), flaring at its base;
//  - the torso: a sweep up the body frame's vertical whose elliptic sections narrow from the
//    chest through the shoulders (acromions) along the trapezius slope into the neck's base;
//  - two arms: sweeps from below the elbows up to the deltoids' domes, which round off the
//    shoulders, hanging a little outwards.
// The body frame is the head's position turned about the vertical by `torso_turn` times the
// head's yaw: the torso follows the head's translation (a walk's bob and sway) and part of its
// turns, as a real torso does when the head looks aside; nods, rolls and the rest of the turn
// happen on the neck.
//
// Drawing: whole surfaces back to front (the arm farther than the torso, the torso, the other
// arm, the neck, the head), each cut where it runs inside a solid drawn before it (a per-vertex
// signed distance, interpolated: the cut follows the true intersection curve). A surface drawn
// earlier stays whole under the later ones, so neighbouring surfaces overlap instead of meeting
// edge to edge, and no seam can open between them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "sim/camera.hpp"
#include "sim/face.hpp"
#include "sim/head.hpp"
#include "sim/params.hpp"
#include "sim/surface_rays.hpp"
#include "sim/sweep.hpp"

namespace wisp::sim {

enum BodyPart : int { kBodyHead = 0, kBodyNeck = 1, kBodyTorso = 2, kBodyArm = 3 };

struct BodyParams {
  bool head = true;   // draw the head
  bool neck = true;   // draw the neck
  bool torso = true;  // draw the torso and the upper arms
  bool face = true;   // with `head`: draw facial features (sim/face.hpp)
  int slices = 96;    // vertices around each surface, 3 to 1024
  int stacks = 48;    // head: rings from pole to pole, 2 to 1024 (sweeps: rings as finely spaced)
  double torso_turn = 0.35;  // the torso's share of the head's yaw, in [0, 1]
  // Torso: along the body frame's +y from `torso_bottom`, `torso_length` long.
  Sweep torso_shape;
  Eigen::Vector3d torso_bottom{0, -0.81, 0};
  double torso_length = 0.645;
  // The arm on the +x side, from its lower end up to the top of its deltoid (body frame); the
  // other arm is its mirror image.
  Sweep arm_shape;
  Eigen::Vector3d arm_bottom{0.2, -0.75, -0.05}, shoulder{0.17, -0.186, -0.028};
  // Neck: from `neck_bottom` (body frame) to `neck_top` (head-local).
  Sweep neck_shape;
  Eigen::Vector3d neck_bottom{0, -0.25, -0.035}, neck_top{0, -0.045, -0.012};
};

// The figure that goes with a head: torso, arms and neck scaled from the head's shoulder fields
// (shoulder_center: the middle of the line between the shoulder joints; shoulder_half_width:
// from there to each joint; shoulder_radius: the shoulders' half depth) and its radii.
BodyParams body_params(const HeadParams& head);

// Throws std::invalid_argument naming the field ("body.neck_shape: ...") for malformed profiles,
// non-finite points, tessellation counts or torso_turn out of range.
void validate(const BodyParams& body);

// The body frame of a pose (see above): body-frame point p is at body_frame(...) * p.
Eigen::Isometry3d body_frame(const HeadPose& pose, double torso_turn);

// The head's yaw (radians, about the world's vertical): the heading of its forward axis.
double head_yaw(const HeadPose& pose);

// The neck, torso and arms for queries (profiles prepared once), like HeadShape for the head.
class BodyShape {
 public:
  enum Solid : int { kNeck = 0, kTorso = 1, kArmPlus = 2, kArmMinus = 3, kSolids = 4 };

  explicit BodyShape(const BodyParams& body);  // validates

  const BodyParams& params() const { return body_; }
  bool drawn(int solid) const { return solid == kNeck ? body_.neck : body_.torso; }

  // A sweep posed in the world: local y along its axis, local point p at frame * p.
  struct Placement {
    Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
    double length = 1;
  };
  Placement placement(const HeadPose& pose, int solid) const;
  const SweepShape& shape(int solid) const;

  // Every solid posed, for many queries at one pose.
  struct Posed {
    Placement at[kSolids];
    Eigen::Isometry3d to_local[kSolids];  // at[s].frame inverted
  };
  Posed posed(const HeadPose& pose) const;

  // Signed distance estimate (negative inside) of world point x to one solid, with the outward
  // unit normal (world). Beyond 5 cm of the solid (SweepShape::lower_bound), that lower bound.
  double solid_distance(int solid, const Posed& at, const Eigen::Vector3d& x,
                        Eigen::Vector3d* normal = nullptr) const;

  // The nearest of the drawn solids (neck if body.neck, torso and arms if body.torso);
  // +infinity when none is drawn.
  double distance(const Posed& at, const Eigen::Vector3d& x,
                  Eigen::Vector3d* normal = nullptr) const;
  double distance(const HeadPose& pose, const Eigen::Vector3d& x,
                  Eigen::Vector3d* normal = nullptr) const {
    return distance(posed(pose), x, normal);
  }

  // Is the segment from `eye` to `x` blocked by a drawn solid, each shrunk by `shrink`, at a
  // distance from the eye below |x - eye| - `ignore`? Sphere tracing on the distance estimates.
  bool blocks(const Posed& at, const Eigen::Vector3d& eye, const Eigen::Vector3d& x, double shrink,
              double ignore) const;
  bool blocks(const HeadPose& pose, const Eigen::Vector3d& eye, const Eigen::Vector3d& x,
              double shrink, double ignore) const {
    return blocks(posed(pose), eye, x, shrink, ignore);
  }

 private:
  BodyParams body_;
  SweepShape neck_, torso_, arm_;
};

// One closed surface of the posed body, in world space.
struct BodySurface {
  int part = kBodyHead;  // BodyPart
  int solid = -1;        // BodyShape::Solid, -1 for the head
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3d> normals;    // unit outward normals of the smooth surface
  std::vector<Eigen::Vector3i> triangles;  // outward counter-clockwise
  // The mesh's edge_neighbours (sim/surface_rays.hpp), found once and shared by its poses; null
  // where the mesh is built per frame.
  std::shared_ptr<const EdgeNeighbours> neighbours;
};

// A surface as the camera sees it. Pixels have x right, y down (as ProjectedStrand::pixel); front
// faces keep their outward counter-clockwise order, which in these axes gives a negative cross
// product (p1 - p0) x (p2 - p0).
struct ProjectedSurface {
  int part = kBodyHead;
  std::vector<Eigen::Vector2d> pixel;  // per vertex
  // Per vertex: the half-Lambert shade (1 + n.l) / 2 in [0,1] of the smooth normal (0 faces
  // away from the light, 1 faces it), and the signed distance in metres to the nearest solid
  // drawn before this surface (+infinity if none): the surface shows where it is positive.
  std::vector<float> shade, clearance;
  // Per vertex: where it sits on its solid, in the solid's own frame (head-local for the head,
  // the sweep's frame for the others): coordinates that move with the surface, for strokes laid
  // on it (apps/render/body_hatching.hpp).
  std::vector<Eigen::Vector3d> local;
  // The front faces whose corners are all in front of the eye and not all inside an earlier
  // solid.
  std::vector<Eigen::Vector3i> triangles;
};

// Surfaces in drawing order: paint each whole over the ones before.
struct ProjectedBody {
  std::vector<ProjectedSurface> surfaces;
};

// The body tessellated once; surfaces() and project() pose it per frame.
class BodyModel {
 public:
  // Throws std::invalid_argument for a bad head geometry or bad body parameters.
  BodyModel(const HeadGeometry& head, const BodyParams& body);

  const BodyParams& params() const { return shape_.params(); }
  const BodyShape& shape() const { return shape_; }
  const HeadShape& head() const { return head_shape_; }

  // The drawn surfaces posed, in drawing order for an eye at `eye`.
  std::vector<BodySurface> surfaces(const HeadPose& pose, const Eigen::Vector3d& eye) const;

  // Triangles with a corner closer to the eye plane than 1 mm (or behind it) are dropped.
  // `light_dir` points towards the light (world space; normalised here; zero gives shade 0.5).
  ProjectedBody project(const HeadPose& pose, const Camera& camera,
                        const Eigen::Vector3d& light_dir) const;

  // The posed head, drawn or not: the same surface as surfaces()' head when it is drawn.
  BodySurface head_surface(const HeadPose& pose) const;

  // The facial features' visible runs (none unless the head and its face are drawn).
  std::vector<FaceStroke> face(const HeadPose& pose, const Camera& camera) const;

  // Signed distance of world point x to the solid of surface `s` (a BodySurface's part/solid).
  double distance(const HeadPose& pose, const BodySurface& s, const Eigen::Vector3d& x) const;

  // Is the segment from `eye` to `x` blocked by a drawn solid, the head included, at a distance
  // from the eye below |x - eye| - `ignore`?
  bool blocks(const HeadPose& pose, const Eigen::Vector3d& eye, const Eigen::Vector3d& x,
              double ignore) const;

 private:
  struct Mesh {
    std::vector<Eigen::Vector3d> vertices, normals;  // local to the solid's frame
    std::vector<Eigen::Vector3i> triangles;
    std::shared_ptr<const EdgeNeighbours> neighbours;
  };
  // Mesh m moved to `frame`, as surface `part` of solid `solid`.
  static BodySurface placed(int part, int solid, const Mesh& m, const Eigen::Isometry3d& frame);
  // The neck's mesh (sweep-local, with neck_neighbours_) at `length`, from neck_'s (t, theta).
  Mesh neck_mesh(double length) const;

  BodyShape shape_;
  HeadShape head_shape_;
  Mesh head_;              // head-local
  Mesh torso_, arm_plus_;  // sweep-local (the other arm uses the same local mesh)
  SweepMesh neck_;         // rebuilt per frame from (t, theta): its length follows the pose
  // The neck's edge neighbours, from its mesh at rest length: its vertices are the same (t,
  // theta) at every length.
  std::shared_ptr<const EdgeNeighbours> neck_neighbours_;
  std::vector<FaceLine> face_;
};

// One-shot form of BodyModel(head, body).project(pose, Camera::look_at(camera), light_dir).
ProjectedBody project_body(const HeadPose& pose, const HeadGeometry& head, const BodyParams& body,
                           const CameraParams& camera, const Eigen::Vector3d& light_dir);

}  // namespace wisp::sim
