// The head and body as the camera sees them: flat 2D triangles with a depth and a shade, sorted
// back to front, for the renderer to paint under the hair (painter's algorithm). Plain data
// (Eigen only, no Bullet); the projection is sim::Camera's, so the body lines up exactly with the
// ProjectedFrames of the hair.
//
// The body has three parts:
//  - the head: the HeadGeometry the strands collided with (an ellipsoid tessellated into
//    `slices` x `stacks` and scaled out so the polyhedron just contains the ellipsoid, or the
//    mesh as it is), posed by the frame's HeadPose;
//  - the neck: a capsule from a point inside the head (head-local: it follows the head's rotation)
//    to a point inside the shoulders (body frame);
//  - the torso: the shoulder capsule (the same capsule strands collide with when head.shoulders
//    is on) and a chest below it, both in the body frame. The chest is a superellipsoid,
//    ((x/a)^2 + (z/c)^2)^(e/2) + |y/b|^e <= 1: elliptic cross-sections, and with the exponent e
//    above 2 nearly straight sides and a flattened top that meets the shoulders.
// The parts overlap (the neck's ends sit inside the head and the shoulders, the shoulders inside
// the chest); a triangle whose corners all lie inside other drawn solids is never visible and is
// dropped, so the painter's order only has the triangles along the seams to get wrong.
// The body frame is the head's position without its rotation, as for the simulation's shoulders
// (sim/head.hpp): the torso follows the head's translation (a walk's bob and sway) but not its
// turns, nods and shakes, which happen on the neck. With head.shoulders on, strands collide with
// the shoulders, the neck and the chest (SimSetup::body), so the drawn body is where the strands
// collided with it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/camera.hpp"
#include "sim/head.hpp"
#include "sim/params.hpp"

namespace wisp::sim {

enum BodyPart : int { kBodyHead = 0, kBodyNeck = 1, kBodyTorso = 2 };

struct BodyParams {
  bool head = true;   // draw the head
  bool neck = true;   // draw the neck
  bool torso = true;  // draw the shoulders and chest
  int slices = 40;    // ellipsoids and capsules: segments around the axis, 3 to 1024
  int stacks = 20;    // and from pole to pole, 2 to 1024 (even for capsules: rounded up)
  // Neck capsule: from `neck_top` (head-local) to `neck_bottom` (body frame), metres.
  Eigen::Vector3d neck_top{0.0, -0.045, -0.012};
  Eigen::Vector3d neck_bottom{0.0, -0.235, -0.03};
  double neck_radius = 0.05;
  // Shoulders: a capsule along x, body frame (see Capsule in sim/head.hpp).
  Capsule shoulders{Eigen::Vector3d(0.0, -0.25, -0.02), 0.16, 0.07};
  // Chest: a superellipsoid, body frame (see above); exponent 2 is an ellipsoid.
  Eigen::Vector3d chest_center{0.0, -0.47, -0.02};
  Eigen::Vector3d chest_radii{0.20, 0.28, 0.095};
  double chest_exponent = 4.0;  // 1 to 16
};

// The body that goes with a head: the shoulder capsule from head.shoulder_* (the collision
// capsule), the neck scaled to the head's radii, the chest hung under the shoulders.
BodyParams body_params(const HeadParams& head);

// Throws std::invalid_argument naming the field ("neck_radius: ...", see validate() in
// sim/params.hpp) for non-finite values, non-positive radii or tessellation counts out of range.
void validate(const BodyParams& body);

// A triangle in pixels (x right, y down, as ProjectedStrand::pixel). Front faces keep their
// outward counter-clockwise order, which in these y-down axes gives a negative cross product
// (p1 - p0) x (p2 - p0).
struct BodyTriangle {
  Eigen::Vector2d p[3];
  double depth = 0;  // distance from the eye to the triangle's centroid (scene units)
  float shade = 0;   // half-Lambert (1 + n.l) / 2 in [0,1]: 0 faces away from the light, 1 faces it
  int part = kBodyHead;  // BodyPart
  // The same shade at each corner from the smooth vertex normal (area-weighted mean of the face
  // normals around the vertex, over the whole part, culled faces included): interpolated across
  // the triangle (Gouraud), a toon band edge runs smoothly across triangles.
  float vertex_shade[3] = {0, 0, 0};
};

// Front-facing triangles only (back faces culled), sorted back to front: draw them in order.
struct ProjectedBody {
  std::vector<BodyTriangle> triangles;
};

// The body tessellated once; project() poses and projects it per frame.
class BodyModel {
 public:
  // Throws std::invalid_argument for a bad head geometry or bad body parameters.
  BodyModel(const HeadGeometry& head, const BodyParams& body);

  const BodyParams& params() const { return body_; }

  // Triangles closer to the eye plane than 1 mm (or behind it) are dropped. `light_dir` points
  // towards the light (world space; normalised here; zero gives shade 0.5 everywhere).
  ProjectedBody project(const HeadPose& pose, const Camera& camera,
                        const Eigen::Vector3d& light_dir) const;

  // The posed body's triangles in world space (columns are the corners), before culling (for
  // tests and debugging). `part` receives each triangle's BodyPart, `normals` its corners' unit
  // vertex normals.
  std::vector<Eigen::Matrix3d> world_triangles(
      const HeadPose& pose, std::vector<int>* part = nullptr,
      std::vector<Eigen::Matrix3d>* normals = nullptr) const;

  // Is world point x inside a drawn solid other than `solid` (0 head, 1 neck, 2 shoulders,
  // 3 chest; -1: any)?
  bool inside_other(const HeadPose& pose, const Eigen::Vector3d& x, int solid) const;

 private:
  BodyParams body_;
  HeadShape shape_;     // inside test for the head
  TriangleMesh head_;   // head-local
  TriangleMesh torso_;  // body frame: the shoulder capsule, then the chest
  std::size_t chest_triangles_ = 0;
  // The neck, rebuilt per frame from a unit capsule: each vertex is a point of the axis (0 = top,
  // 1 = bottom) plus an offset of radius 1 in the frame whose z runs from the top to the bottom.
  std::vector<Eigen::Vector3d> neck_offset_;
  std::vector<double> neck_along_;
  std::vector<Eigen::Vector3i> neck_triangles_;
};

// One-shot form of BodyModel(head, body).project(pose, Camera::look_at(camera), light_dir).
ProjectedBody project_body(const HeadPose& pose, const HeadGeometry& head, const BodyParams& body,
                           const CameraParams& camera, const Eigen::Vector3d& light_dir);

// Signed distance (negative inside, metres) from world point x to the neck (if body.neck) and the
// chest (if body.torso) posed by `pose`, the nearer of the two, with its outward unit normal.
// The shoulder capsule is not included (the simulation handles it as before). For the chest,
// the first-order estimate (F - 1) / |grad F| with F = (superellipsoid value)^(1/e), exact on
// the surface; beyond 5 cm from the chest's bounding box, the distance to that box (a lower
// bound). +infinity when neither part is on.
double body_distance(const BodyParams& body, const HeadPose& pose, const Eigen::Vector3d& x,
                     Eigen::Vector3d* normal = nullptr);

// Is the segment from `eye` to `x` blocked by the neck or torso of `body` (only the parts it
// draws) posed by `pose`, at a distance from the eye below |x - eye| - `ignore`? Each shape's
// radii are reduced by `shrink` first. Analytic capsules and ellipsoid (not the tessellation).
bool body_blocks(const BodyParams& body, const HeadPose& pose, const Eigen::Vector3d& eye,
                 const Eigen::Vector3d& x, double shrink, double ignore);

}  // namespace wisp::sim
