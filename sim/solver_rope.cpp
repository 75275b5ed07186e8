// The comparison baseline (sim.model = "rope"): every guide is a Bullet soft-body rope in a
// btSoftRigidDynamicsWorld, the way Costigan (2013) built cartoon hair: mass-spring links between
// consecutive samples and bending links two apart (generateBendingConstraints), solved by
// sim.iterations position passes, root node massless and moved with the head, collisions with the
// head as a kinematic rigid body through Bullet's own soft-rigid contacts (an ellipsoid, or the
// mesh's convex hull). Links are springs, so ropes stretch: wisp-bench sim measures how much.
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "sim/solver.hpp"

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

btVector3 bt(const Vector3d& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

btTransform bt_pose(const HeadPose& pose) {
  const Eigen::Quaterniond& q = pose.rotation;
  return btTransform(
      btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
      bt(pose.position));
}

class RopeSolver final : public StrandSolver {
 public:
  RopeSolver(const Environment& env, const std::vector<Polyline>& rest)
      : env_(env), dispatcher_(&config_), world_(&dispatcher_, &broadphase_, &solver_, &config_) {
    const SimParams& sp = env.params();
    world_.setGravity(bt(sp.gravity));
    btSoftBodyWorldInfo& info = world_.getWorldInfo();
    info.m_gravity = bt(sp.gravity);
    info.air_density = 0;
    info.water_density = 0;
    info.m_dispatcher = &dispatcher_;
    info.m_broadphase = &broadphase_;
    info.m_sparsesdf.Initialize();

    // The head: a kinematic rigid body.
    const HeadGeometry& g = env.head().geometry();
    if (g.shape == HeadKind::Ellipsoid) {
      const btVector3 centre(0, 0, 0);
      const btScalar radius = 1;
      auto sphere = std::make_unique<btMultiSphereShape>(&centre, &radius, 1);
      sphere->setLocalScaling(bt(g.radii));
      head_shape_ = std::move(sphere);
    } else {
      auto hull = std::make_unique<btConvexHullShape>();
      for (const Vector3d& v : g.mesh.vertices) hull->addPoint(bt(v), false);
      hull->recalcLocalAabb();
      head_shape_ = std::move(hull);
    }
    head_shape_->setMargin(btScalar(0.001));
    btRigidBody::btRigidBodyConstructionInfo ci(0, &head_motion_, head_shape_.get());
    head_ = std::make_unique<btRigidBody>(ci);
    head_->setCollisionFlags(head_->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    head_->setActivationState(DISABLE_DEACTIVATION);
    set_head(env.motion().pose(0));
    if (sp.collision) world_.addRigidBody(head_.get());

    const HeadPose pose0 = env.motion().pose(0);
    for (const Polyline& strand : rest) {
      const int n = static_cast<int>(strand.size());
      std::vector<btVector3> x(n);
      std::vector<btScalar> m(n);
      for (int i = 0; i < n; ++i) {
        x[i] = bt(pose0.to_world(strand[i]));
        const double l_prev = i > 0 ? (strand[i] - strand[i - 1]).norm() : 0.0;
        const double l_next = i + 1 < n ? (strand[i + 1] - strand[i]).norm() : 0.0;
        m[i] = i == 0 ? 0 : btScalar(sp.density * 0.5 * (l_prev + l_next));
      }
      auto rope = std::make_unique<btSoftBody>(&info, n, x.data(), m.data());
      btSoftBody::Material* stretch = rope->appendMaterial();
      stretch->m_kLST = 1;
      for (int i = 0; i + 1 < n; ++i) rope->appendLink(i, i + 1, stretch);
      btSoftBody::Material* bend = rope->appendMaterial();
      bend->m_kLST = btScalar(std::clamp(sp.bend_stiffness / 1e-4, 0.01, 1.0));
      rope->generateBendingConstraints(2, bend);
      rope->m_cfg.piterations = sp.iterations;
      rope->m_cfg.kDP = btScalar(std::min(0.5, sp.damping / (sp.step_rate * sp.substeps)));
      rope->m_cfg.kDF = 0.2f;
      rope->getCollisionShape()->setMargin(btScalar(sp.collision_margin));
      world_.addSoftBody(rope.get());
      roots_.push_back(strand[0]);
      ropes_.push_back(std::move(rope));
    }
  }

  ~RopeSolver() override {
    for (auto& r : ropes_) world_.removeSoftBody(r.get());
    if (env_.params().collision) world_.removeRigidBody(head_.get());
  }

  void step(double t, double dt) override {
    const int sub = env_.params().substeps;
    const double h = dt / sub;
    for (int k = 0; k < sub; ++k) {
      const HeadPose pose = env_.motion().pose(t + (k + 1) * h);
      set_head(pose);
      for (std::size_t s = 0; s < ropes_.size(); ++s) {
        btSoftBody::Node& root = ropes_[s]->m_nodes[0];
        const btVector3 x = bt(pose.to_world(roots_[s]));
        root.m_v = (x - root.m_x) / btScalar(h);
        root.m_x = x;
        root.m_q = x;
      }
      world_.stepSimulation(btScalar(h), 0, btScalar(h));
      world_.getWorldInfo().m_sparsesdf.GarbageCollect();
    }
    max_speed_ = 0;
    for (const auto& r : ropes_)
      for (int i = 0; i < r->m_nodes.size(); ++i) {
        const double v = r->m_nodes[i].m_v.length();
        max_speed_ = std::isfinite(v) ? std::max(max_speed_, v) : INFINITY;
      }
  }

  void positions(std::vector<Polyline>& out) const override {
    out.resize(ropes_.size());
    for (std::size_t s = 0; s < ropes_.size(); ++s) {
      const btSoftBody& r = *ropes_[s];
      out[s].resize(r.m_nodes.size());
      for (int i = 0; i < r.m_nodes.size(); ++i) {
        const btVector3& x = r.m_nodes[i].m_x;
        out[s][i] = Vector3d(x.x(), x.y(), x.z());
      }
    }
  }

  double max_speed() const override { return max_speed_; }

 private:
  const Environment& env_;
  btSoftBodyRigidBodyCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btSoftRigidDynamicsWorld world_;
  btDefaultMotionState head_motion_;
  std::unique_ptr<btCollisionShape> head_shape_;
  std::unique_ptr<btRigidBody> head_;
  std::vector<std::unique_ptr<btSoftBody>> ropes_;
  std::vector<Vector3d> roots_;
  double max_speed_ = 0;

  void set_head(const HeadPose& pose) {
    const btTransform t = bt_pose(pose);
    head_motion_.setWorldTransform(t);
    head_->setWorldTransform(t);
  }
};

}  // namespace

std::unique_ptr<StrandSolver> make_rope_solver(const Environment& env,
                                               const std::vector<Polyline>& rest) {
  return std::make_unique<RopeSolver>(env, rest);
}

}  // namespace wisp::sim
