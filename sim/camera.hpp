// The pinhole look-at camera and the projection of simulated frames into ProjectedFrames (the
// contract with vector/, sim/projected.hpp): pixel position, depth (distance to the eye), world
// position, unit 3D tangent and head occlusion per strand sample.
//
// Occlusion: a Bullet ray test from the eye to each sample against the head's collision shape
// (btMultiSphereShape scaled to the ellipsoid, or a btBvhTriangleMeshShape); hits within
// `hysteresis` of the sample are ignored, since hair lies on the scalp. Visibility changes with
// hysteresis over frames, so samples near the head's silhouette do not flicker: a visible sample
// becomes hidden only when the ray is blocked by the head shrunk by `hysteresis`, a hidden one
// becomes visible only when the ray clears the full head; in between it keeps its state.
//
// With ProjectorOptions::body, the drawn neck, torso and arms (sim/body.hpp) hide strands too,
// with the same hysteresis (sphere tracing on their analytic distances, shrunk by `hysteresis`
// for the inner test).
// Every frame carries ProjectorOptions::light_dir (the scene's light) and the head's crown axis
// for shading.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "sim/animation.hpp"
#include "sim/params.hpp"
#include "sim/projected.hpp"

namespace wisp::sim {

struct Camera {
  Eigen::Vector3d eye, forward, right, up;  // orthonormal: right = forward x up
  double focal_px = 0;
  int width = 0, height = 0;

  // Throws std::invalid_argument naming the camera field for a degenerate camera.
  static Camera look_at(const CameraParams& params);

  // Pixel position (x right, y down) of a world point and its distance to the eye. Points behind
  // the eye project as if just in front of it; callers mark them hidden.
  Eigen::Vector2d project(const Eigen::Vector3d& world, double* depth = nullptr) const;
};

struct BodyParams;
class BodyShape;

struct ProjectorOptions {
  Eigen::Vector3d light_dir = default_light_dir();  // copied into every frame (normalised)
  std::shared_ptr<const BodyParams> body;           // occluding neck, torso, arms; null: none
  // Per strand: copied into ProjectedStrand::width (sim::Animation::widths); empty: none.
  std::vector<std::vector<double>> widths;
};

class Projector {
 public:
  // Throws std::invalid_argument for a degenerate camera or a zero light direction.
  Projector(const HeadGeometry& head, const CameraParams& camera,
            const ProjectorOptions& options = {});
  ~Projector();

  const Camera& camera() const { return camera_; }

  // Projects one frame. Frames should come in order: visibility hysteresis uses the previous
  // call's result (the first call, or a change of strand layout, starts afresh).
  ProjectedFrame project(const StrandFrame& frame);

 private:
  struct Bullet;
  Camera camera_;
  double hysteresis_;
  ProjectorOptions options_;
  std::unique_ptr<Bullet> bullet_;
  std::unique_ptr<const BodyShape> body_;
  std::vector<std::vector<std::uint8_t>> visible_;
};

}  // namespace wisp::sim
