// Strand solver on Bullet's Featherstone multibodies: one btMultiBody chain per guide, one link per
// segment joined by spherical joints (reduced coordinates: a strand cannot stretch), in a
// btMultiBodyDynamicsWorld.
//
// The chains live in the head's frame with a fixed base at the root, so the roots follow the head
// exactly; the frame is not inertial, so every link gets the fictitious forces of the head's
// motion, -m (a + alpha x r + w x (w x r) + 2 w x v_rel), besides gravity and drag, all through
// addLinkForce. Bending towards the rest shape is a spring-damper joint torque
// tau = -k theta - c qdot, theta the rotation vector from the rest joint orientation, k = EI / l
// (explicit: too stiff a spring for the step blows up, and the driver reports it).
//
// Head contact does not use Bullet's link colliders: measured, multibody contacts against a head
// cost 30x the dynamics (150 x 16 links: 10 s per simulated second). Instead a penalty force
// against the head's signed distance, k (margin - d) n plus damping of the approach speed, pushes
// each link's tip out, k chosen from the link mass and the step so the contact stays stable.
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sim/solver.hpp"

namespace wisp::sim {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

constexpr double kJointDampingRatio = 0.5;

btVector3 bt(const Vector3d& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}
Vector3d eig(const btVector3& v) {
  return Vector3d(v.x(), v.y(), v.z());
}

// Head velocity, angular velocity and their derivatives at t (world frame), by central
// differences of the keyframed motion.
struct HeadKinematics {
  HeadPose pose;
  Vector3d vel, acc, omega, alpha;
};

Vector3d angular_velocity(const HeadMotion& m, double t, double eps) {
  const Quaterniond a = m.pose(t - eps).rotation, b = m.pose(t + eps).rotation;
  const Eigen::AngleAxisd d(b * a.conjugate());
  return d.axis() * d.angle() / (2 * eps);
}

HeadKinematics head_kinematics(const HeadMotion& m, double t) {
  constexpr double eps = 1e-3;
  HeadKinematics k;
  k.pose = m.pose(t);
  const Vector3d p0 = m.pose(t - eps).position, p1 = m.pose(t + eps).position;
  k.vel = (p1 - p0) / (2 * eps);
  k.acc = (p1 - 2 * k.pose.position + p0) / (eps * eps);
  k.omega = angular_velocity(m, t, eps);
  k.alpha = (angular_velocity(m, t + eps, eps) - angular_velocity(m, t - eps, eps)) / (2 * eps);
  return k;
}

class FeatherstoneSolver final : public StrandSolver {
 public:
  FeatherstoneSolver(const Environment& env, const std::vector<Polyline>& rest)
      : env_(env), dispatcher_(&config_), world_(&dispatcher_, &broadphase_, &solver_, &config_) {
    world_.setGravity(btVector3(0, 0, 0));  // gravity is applied in the head frame, by hand
    const SimParams& sp = env.params();
    // Bullet works in float and is tuned for bodies of about a kilogram; hair links weigh tens of
    // milligrams, and their inertias (1e-9 kg m^2) made the articulated-body solve lose all
    // precision and blow up. Scaling every mass, force and torque by the same factor leaves the
    // motion unchanged and makes a typical link weigh 1 (in scaled units).
    double mean_length = 0;
    int segments = 0;
    for (const Polyline& strand : rest)
      for (std::size_t i = 1; i < strand.size(); ++i, ++segments)
        mean_length += (strand[i] - strand[i - 1]).norm();
    const double mass_scale = segments > 0 ? segments / (sp.density * mean_length) : 1.0;
    for (const Polyline& strand : rest) {
      Chain c;
      const int links = static_cast<int>(strand.size()) - 1;
      c.root = strand[0];
      c.body = std::make_unique<btMultiBody>(links, btScalar(1), btVector3(1, 1, 1), true, false);
      btMultiBody& mb = *c.body;
      mb.setBasePos(bt(strand[0]));
      mb.setWorldToBaseRot(btQuaternion::getIdentity());
      // Link frames: segment along local +z, parallel-transported (no twist) along the rest shape.
      Quaterniond frame = Quaterniond::Identity();
      Vector3d axis = Vector3d::UnitZ();
      for (int i = 0; i < links; ++i) {
        const Vector3d seg = strand[i + 1] - strand[i];
        const double l = seg.norm();
        const double m = mass_scale * sp.density * l;
        c.length.push_back(l);
        c.mass.push_back(m);
        const Quaterniond turned = Quaterniond::FromTwoVectors(axis, seg / l) * frame;
        const Quaterniond joint = frame.conjugate() * turned;  // child to parent
        frame = turned;
        axis = seg / l;
        const double inertia = m * l * l / 12;
        const btVector3 parent_com_to_pivot =
            i == 0 ? btVector3(0, 0, 0) : btVector3(0, 0, btScalar(c.length[i - 1] / 2));
        mb.setupSpherical(i, btScalar(m), btVector3(inertia, inertia, inertia), i - 1,
                          btQuaternion::getIdentity(), parent_com_to_pivot,
                          btVector3(0, 0, btScalar(l / 2)), true);
        c.rest_joint.push_back(joint);
      }
      mb.finalizeMultiDof();
      for (int i = 0; i < links; ++i) {
        const Quaterniond& q = c.rest_joint[i];
        const btScalar qv[4] = {btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())};
        mb.setJointPosMultiDof(i, qv);
      }
      mb.setLinearDamping(0);
      mb.setAngularDamping(0);
      mb.setMaxCoordinateVelocity(btScalar(1e4));
      mb.setCanSleep(false);
      // Joint stiffness k = EI / l (curvature theta / l). Damping c = I (damping + 2 zeta omega)
      // with I the link's own inertia about its pivot (a joint's articulated inertia can be as
      // small as that) and omega = sqrt(k / I): the joint springs are half-critically damped.
      // Without that stiffness-proportional part the chains whip (measured: tips above 20 m/s
      // within a second of `shake`, then the explicit springs blow up), where DFTL's velocity
      // correction damps the same modes.
      for (int i = 0; i < links; ++i) {
        const double lbar = i == 0 ? c.length[0] : 0.5 * (c.length[i - 1] + c.length[i]);
        double k = mass_scale * sp.bend_stiffness / lbar;
        if (i == 0) k *= sp.root_stiffness;
        const double inertia = c.mass[i] * c.length[i] * c.length[i] / 3;
        c.stiffness.push_back(k);
        c.damping.push_back(inertia *
                            (sp.damping + 2 * kJointDampingRatio * std::sqrt(k / inertia)));
      }
      world_.addMultiBody(c.body.get());
      chains_.push_back(std::move(c));
    }
    omega_.resize(64);
    vel_.resize(64);
  }

  ~FeatherstoneSolver() override {
    for (Chain& c : chains_) world_.removeMultiBody(c.body.get());
  }

  void step(double t, double dt) override {
    const int sub = env_.params().substeps;
    const double h = dt / sub;
    max_speed_ = 0;
    for (int k = 0; k < sub; ++k) {
      apply_forces(t + k * h, h);
      world_.stepSimulation(btScalar(h), 0, btScalar(h));
    }
  }

  void positions(std::vector<Polyline>& out) const override {
    const HeadPose pose = env_.motion().pose(time_);
    out.resize(chains_.size());
    std::vector<Quaterniond> frames;
    for (std::size_t s = 0; s < chains_.size(); ++s) {
      Polyline local;
      kinematics(chains_[s], local, frames);
      out[s].resize(local.size());
      for (std::size_t i = 0; i < local.size(); ++i) out[s][i] = pose.to_world(local[i]);
    }
  }

  double max_speed() const override { return max_speed_; }

 private:
  struct Chain {
    Vector3d root;
    std::unique_ptr<btMultiBody> body;
    std::vector<double> length, mass, stiffness, damping;
    std::vector<Quaterniond> rest_joint;
  };

  const Environment& env_;
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btMultiBodyConstraintSolver solver_;
  btMultiBodyDynamicsWorld world_;
  std::vector<Chain> chains_;
  std::vector<btVector3> omega_, vel_;
  double max_speed_ = 0, time_ = 0;

  // Head-local sample positions and link frames (link to head) from the joint quaternions.
  static void kinematics(const Chain& c, Polyline& nodes, std::vector<Quaterniond>& frames) {
    const btMultiBody& mb = *c.body;
    const int links = mb.getNumLinks();
    nodes.assign(1, c.root);
    frames.clear();
    Quaterniond f = Quaterniond::Identity();
    for (int i = 0; i < links; ++i) {
      const btScalar* q = mb.getJointPosMultiDof(i);
      f = f * Quaterniond(q[3], q[0], q[1], q[2]).normalized();
      frames.push_back(f);
      nodes.push_back(nodes.back() + f * Vector3d(0, 0, c.length[i]));
    }
  }

  void apply_forces(double t, double h) {
    const SimParams& sp = env_.params();
    const HeadKinematics hk = head_kinematics(env_.motion(), t);
    time_ = t + h;
    const Quaterniond to_local = hk.pose.rotation.conjugate();
    const Vector3d g = to_local * sp.gravity, a = to_local * hk.acc, w = to_local * hk.omega,
                   alpha = to_local * hk.alpha, head_vel = to_local * hk.vel;
    Polyline nodes;
    std::vector<Quaterniond> frames;
    for (Chain& c : chains_) {
      btMultiBody& mb = *c.body;
      const int links = mb.getNumLinks();
      mb.clearForcesAndTorques();
      kinematics(c, nodes, frames);
      if (static_cast<int>(omega_.size()) < links + 1) {
        omega_.resize(links + 1);
        vel_.resize(links + 1);
      }
      mb.compTreeLinkVelocities(omega_.data(), vel_.data());
      for (int i = 0; i < links; ++i) {
        const double m = c.mass[i];
        const Vector3d com = 0.5 * (nodes[i] + nodes[i + 1]);
        const Vector3d v_rel = frames[i] * eig(vel_[i + 1]);
        const Vector3d w_link = frames[i] * eig(omega_[i + 1]);
        max_speed_ = std::max(max_speed_, v_rel.norm());
        if (!v_rel.allFinite() || !com.allFinite()) max_speed_ = INFINITY;
        Vector3d f = m * (g - a - alpha.cross(com) - w.cross(w.cross(com)) - 2 * w.cross(v_rel));
        if (sp.air_drag > 0) {
          const Vector3d v_abs = head_vel + w.cross(com) + v_rel;
          const Vector3d wind = to_local * env_.wind(t, hk.pose.to_world(com));
          f += m * sp.air_drag * (wind - v_abs);
        }
        mb.addLinkForce(i, bt(f));
        if (sp.collision) {
          // Penalty contact at the link's tip.
          const Vector3d tip = nodes[i + 1];
          Vector3d n;
          const double d = env_.distance(hk.pose.to_world(tip), hk.pose, &n);
          if (d < sp.collision_margin) {
            n = to_local * n;
            // A link's tip can weigh as little as m / 4 (rotation about its centre), so the
            // spring and damper are set for that mass to stay stable: omega h = 0.5.
            const double omega_c = 0.25 / h;
            const Vector3d v_tip = v_rel + w_link.cross(tip - com);
            const double vn = v_tip.dot(n);
            const Vector3d fc =
                m *
                (omega_c * omega_c * (sp.collision_margin - d) - (vn < 0 ? omega_c * vn : 0.0)) * n;
            mb.addLinkForce(i, bt(fc));
            mb.addLinkTorque(i, bt((tip - com).cross(fc)));
          }
        }
        // Bending spring towards the rest joint orientation (child frame, as the joint dofs).
        const btScalar* q = mb.getJointPosMultiDof(i);
        const btScalar* qd = mb.getJointVelMultiDof(i);
        Quaterniond err = c.rest_joint[i].conjugate() * Quaterniond(q[3], q[0], q[1], q[2]);
        if (err.w() < 0) err.coeffs() *= -1;
        const Eigen::AngleAxisd aa(err);
        const Vector3d theta = aa.axis() * aa.angle();
        const Vector3d tau = -c.stiffness[i] * theta - c.damping[i] * Vector3d(qd[0], qd[1], qd[2]);
        for (int k = 0; k < 3; ++k) mb.addJointTorqueMultiDof(i, k, btScalar(tau[k]));
      }
    }
  }
};

}  // namespace

std::unique_ptr<StrandSolver> make_featherstone_solver(const Environment& env,
                                                       const std::vector<Polyline>& rest) {
  return std::make_unique<FeatherstoneSolver>(env, rest);
}

}  // namespace wisp::sim
