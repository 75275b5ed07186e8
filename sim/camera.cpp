// Camera and Projector: see camera.hpp.
#include "sim/camera.hpp"

#include <BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h>
#include <btBulletCollisionCommon.h>

#include <cmath>
#include <stdexcept>

#include "sim/body.hpp"

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

btVector3 bt(const Vector3d& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

}  // namespace

Camera Camera::look_at(const CameraParams& p) {
  validate_part(p, "camera");
  Camera c;
  c.eye = p.eye;
  c.forward = (p.target - p.eye).normalized();
  c.right = c.forward.cross(p.up).normalized();
  c.up = c.right.cross(c.forward);
  c.width = p.width;
  c.height = p.height;
  c.focal_px = 0.5 * p.height / std::tan(0.5 * p.fov_deg * M_PI / 180);
  return c;
}

Eigen::Vector2d Camera::project(const Vector3d& world, double* depth) const {
  const Vector3d d = world - eye;
  if (depth) *depth = d.norm();
  const double z = std::max(d.dot(forward), 1e-6);
  return {0.5 * width + focal_px * d.dot(right) / z, 0.5 * height - focal_px * d.dot(up) / z};
}

// The head as Bullet collision objects: full size and shrunk by the hysteresis band.
struct Projector::Bullet {
  std::unique_ptr<btTriangleMesh> mesh;
  std::unique_ptr<btCollisionShape> outer_shape, inner_shape;
  btCollisionObject outer, inner;
};

Projector::Projector(const HeadGeometry& head, const CameraParams& camera,
                     const ProjectorOptions& options)
    : camera_(Camera::look_at(camera)),
      hysteresis_(camera.hysteresis),
      options_(options),
      bullet_(new Bullet) {
  if (!(options_.light_dir.norm() > 1e-12) || !options_.light_dir.allFinite())
    throw std::invalid_argument("light.direction: must be a finite non-zero vector");
  options_.light_dir.normalize();
  if (options_.body) body_ = std::make_unique<const BodyShape>(*options_.body);
  Bullet& b = *bullet_;
  if (head.shape == HeadKind::Ellipsoid) {
    const btVector3 centre(0, 0, 0);
    const btScalar radius = 1;
    auto outer = std::make_unique<btMultiSphereShape>(&centre, &radius, 1);
    outer->setLocalScaling(bt(head.radii));
    auto inner = std::make_unique<btMultiSphereShape>(&centre, &radius, 1);
    inner->setLocalScaling(bt((head.radii - Vector3d::Constant(hysteresis_)).cwiseMax(1e-4)));
    b.outer_shape = std::move(outer);
    b.inner_shape = std::move(inner);
  } else {
    b.mesh = std::make_unique<btTriangleMesh>();
    for (const auto& t : head.mesh.triangles)
      b.mesh->addTriangle(bt(head.mesh.vertices[t[0]]), bt(head.mesh.vertices[t[1]]),
                          bt(head.mesh.vertices[t[2]]));
    auto outer = std::make_unique<btBvhTriangleMeshShape>(b.mesh.get(), true);
    // Shrink about the head-local origin (the head's centre for sensible meshes).
    double extent = 0;
    for (const auto& v : head.mesh.vertices) extent = std::max(extent, v.norm());
    const double s = std::max(0.5, 1 - hysteresis_ / std::max(extent, 1e-3));
    b.inner_shape = std::make_unique<btScaledBvhTriangleMeshShape>(
        outer.get(), btVector3(btScalar(s), btScalar(s), btScalar(s)));
    b.outer_shape = std::move(outer);
  }
  b.outer.setCollisionShape(b.outer_shape.get());
  b.inner.setCollisionShape(b.inner_shape.get());
}

Projector::~Projector() = default;

ProjectedFrame Projector::project(const StrandFrame& frame) {
  Bullet& b = *bullet_;
  const Eigen::Quaterniond& q = frame.head.rotation;
  const btTransform pose(
      btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
      bt(frame.head.position));
  b.outer.setWorldTransform(pose);
  b.inner.setWorldTransform(pose);
  const btTransform from(btQuaternion::getIdentity(), bt(camera_.eye));

  // Is the ray from the eye to `x` blocked by `obj` (or the body, shrunk by `shrink`) clearly
  // before reaching x?
  std::optional<BodyShape::Posed> body;
  if (body_) body = body_->posed(frame.head);
  const auto blocked = [&](btCollisionObject& obj, const Vector3d& x, double dist, double shrink) {
    if (body && body_->blocks(*body, camera_.eye, x, shrink, hysteresis_)) return true;
    const btTransform to(btQuaternion::getIdentity(), bt(x));
    btCollisionWorld::ClosestRayResultCallback cb(from.getOrigin(), to.getOrigin());
    btCollisionWorld::rayTestSingle(from, to, &obj, obj.getCollisionShape(),
                                    obj.getWorldTransform(), cb);
    return cb.hasHit() && cb.m_closestHitFraction * dist < dist - hysteresis_;
  };

  bool fresh = visible_.size() != frame.strands.size();
  for (std::size_t s = 0; !fresh && s < frame.strands.size(); ++s)
    fresh = visible_[s].size() != frame.strands[s].size();
  if (fresh) visible_.assign(frame.strands.size(), {});

  ProjectedFrame out;
  out.frame = frame.frame;
  out.time = frame.time;
  out.width = camera_.width;
  out.height = camera_.height;
  out.focal_px = camera_.focal_px;
  out.eye = camera_.eye;
  out.light_dir = options_.light_dir;
  out.head_up = frame.head.rotation * Vector3d::UnitY();
  out.strands.resize(frame.strands.size());
  for (std::size_t s = 0; s < frame.strands.size(); ++s) {
    const Polyline& line = frame.strands[s];
    ProjectedStrand& ps = out.strands[s];
    const std::size_t n = line.size();
    ps.id = static_cast<int>(s);
    ps.pixel.resize(n);
    ps.depth.resize(n);
    ps.world = line;
    ps.tangent.resize(n);
    ps.visible.resize(n);
    if (s < options_.widths.size()) ps.width = options_.widths[s];
    if (fresh) visible_[s].assign(n, 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Vector3d& x = line[i];
      ps.pixel[i] = camera_.project(x, &ps.depth[i]);
      const Vector3d d = n < 2        ? Vector3d::UnitY()
                         : i == 0     ? Vector3d(line[1] - line[0])
                         : i + 1 == n ? Vector3d(line[n - 1] - line[n - 2])
                                      : Vector3d(line[i + 1] - line[i - 1]);
      ps.tangent[i] = d.norm() > 0 ? Vector3d(d.normalized()) : Vector3d::UnitY();
      std::uint8_t vis;
      if ((x - camera_.eye).dot(camera_.forward) <= 1e-6) {
        vis = 0;  // behind the eye
      } else {
        const bool outer_blocks = blocked(b.outer, x, ps.depth[i], 0.0);
        if (!outer_blocks)
          vis = 1;
        else if (fresh || blocked(b.inner, x, ps.depth[i], hysteresis_))
          vis = 0;
        else
          vis = visible_[s][i];
      }
      ps.visible[i] = vis;
      visible_[s][i] = vis;
    }
  }
  return out;
}

}  // namespace wisp::sim
