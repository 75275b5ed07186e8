// Our default strand solver: Dynamic Follow-The-Leader (Mueller, Kim, Chentanez, "Fast Simulation
// of Inextensible Hair and Fur", VRIPHYS 2012) with local shape matching for the rest shape.
//
// Per sub-step of length h, for each guide (root kinematic, driven by the head):
//  1. predict p = x + h v after gravity and implicit air drag towards the wind;
//  2. sim.iterations Gauss-Seidel passes of
//     - the root clamp: samples 1-3 pulled towards their rest place in the head frame (stiffness
//       sim.root_stiffness x the bending stiffness; 0 leaves a free pivot);
//     - local shape matching (Mueller et al. 2005) over every window of 4 consecutive samples:
//       the best rotation R of the window's rest shape onto its current shape (warm-started
//       rotation extraction, Mueller et al. 2016), and each sample pulled towards
//       c + R (x0 - c0) by the implicit-spring factor h^2 k w / (1 + h^2 k w), k = EI / l^3.
//       Because R is optimal, these pulls are the exact gradient of an energy and keep linear and
//       angular momentum: curls hold without pumping energy, and a stiff strand swings like a
//       rigid rod. (Targets in frames carried along the strand are not conservative: an earlier
//       version of this solver let curls flutter and unwind with gravity off.) Four samples per
//       window hold torsion too, so a curl keeps its handedness;
//     - stretch: |x_{i+1} - x_i| = l_i, mass-weighted (momentum-preserving);
//  3. the follow-the-leader pass, root to tip, puts every sample exactly at its rest distance
//     from its parent: lengths are exact whatever the iterations (Mueller's guarantee); a sample
//     that lands within the collision margin of the head (signed distance) slides out and back
//     onto the sphere around its parent, so collisions never cost length;
//  4. v = (p - x) / h - s (d_{i+1} / h), Mueller's velocity correction with the FTL move d of the
//     next sample, then internal damping of relative velocities.
// Head queries go through the environment (sim/solver.hpp).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sim/solver.hpp"

namespace wisp::sim {
namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

constexpr double kFtlDamping = 0.9;  // Mueller's s_damp
constexpr int kWindow = 4;           // samples per shape-matching window

// One step of Mueller et al.'s rotation extraction: turns q towards the rotation part of A.
void extract_rotation(const Matrix3d& a, Quaterniond& q) {
  const Matrix3d r = q.toRotationMatrix();
  const Vector3d omega =
      r.col(0).cross(a.col(0)) + r.col(1).cross(a.col(1)) + r.col(2).cross(a.col(2));
  const double denom =
      std::abs(r.col(0).dot(a.col(0)) + r.col(1).dot(a.col(1)) + r.col(2).dot(a.col(2))) + 1e-12;
  const Vector3d w = omega / denom;
  if (w.squaredNorm() < 1e-24) return;
  // The warm-started correction is small: (1, w/2) normalized is its rotation to third order,
  // without the sine and cosine (a tenth of the solver's time otherwise).
  q = Quaterniond(1, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized() * q;
  q.normalize();
}

class DftlSolver final : public StrandSolver {
 public:
  DftlSolver(const Environment& env, const std::vector<Polyline>& rest) : env_(env) {
    const SimParams& sp = env.params();
    const HeadPose pose0 = env.motion().pose(0);
    for (const Polyline& strand : rest) {
      const int n = static_cast<int>(strand.size());
      Strand s;
      s.begin = static_cast<int>(x_.size());
      s.n = n;
      s.windows = std::max(1, n - kWindow + 1);
      s.window_begin = static_cast<int>(window_rot_.size());
      double total = 0;
      for (int i = 0; i < n; ++i) {
        x_.push_back(pose0.to_world(strand[i]));
        v_.push_back(Vector3d::Zero());
        rest_local_.push_back(strand[i]);
        const double l_prev = i > 0 ? (strand[i] - strand[i - 1]).norm() : 0.0;
        const double l_next = i + 1 < n ? (strand[i + 1] - strand[i]).norm() : 0.0;
        length_.push_back(l_next);
        total += l_next;
        const double m = sp.density * 0.5 * (l_prev + l_next);
        mass_.push_back(m);
        w_.push_back(i == 0 ? 0.0 : 1.0 / m);
      }
      const double l = total / (n - 1);
      s.bend_k = sp.bend_stiffness / (l * l * l);
      s.root_k = s.bend_k * sp.root_stiffness;
      // Rotations start at the head's orientation: the rest shape is in head coordinates.
      for (int w = 0; w < s.windows; ++w) window_rot_.push_back(pose0.rotation);
      strands_.push_back(s);
    }
    p_.resize(x_.size());
    dv_.resize(x_.size());
  }

  void step(double t, double dt) override {
    const int sub = env_.params().substeps;
    const double h = dt / sub;
    max_speed_ = 0;
    for (int k = 0; k < sub; ++k) substep(t + k * h, h);
  }

  void positions(std::vector<Polyline>& out) const override {
    out.resize(strands_.size());
    for (std::size_t s = 0; s < strands_.size(); ++s)
      out[s].assign(x_.begin() + strands_[s].begin, x_.begin() + strands_[s].begin + strands_[s].n);
  }

  double max_speed() const override { return max_speed_; }

 private:
  struct Strand {
    int begin = 0, n = 0;
    int windows = 0, window_begin = 0;
    double bend_k = 0, root_k = 0;  // N/m
  };

  const Environment& env_;
  std::vector<Strand> strands_;
  std::vector<Vector3d> x_, v_, p_, dv_, rest_local_;
  std::vector<double> w_, mass_, length_;
  std::vector<Quaterniond> window_rot_;
  double max_speed_ = 0;

  // Pulls the window [a, a + count) of p towards its rest shape, rotated by the best rotation.
  void match_window(Vector3d* p, const Vector3d* rest, const double* m, const double* w, int count,
                    Quaterniond& q, double h2k) {
    Vector3d c = Vector3d::Zero(), c0 = Vector3d::Zero();
    double msum = 0;
    for (int j = 0; j < count; ++j) {
      // The kinematic root weighs as its neighbour; it does not move anyway.
      const double mj = w[j] > 0 ? m[j] : m[std::min(j + 1, count - 1)];
      c += mj * p[j];
      c0 += mj * rest[j];
      msum += mj;
    }
    c /= msum;
    c0 /= msum;
    Matrix3d a = Matrix3d::Zero();
    for (int j = 0; j < count; ++j) {
      const double mj = w[j] > 0 ? m[j] : m[std::min(j + 1, count - 1)];
      a += mj * (p[j] - c) * (rest[j] - c0).transpose();
    }
    extract_rotation(a, q);
    const Matrix3d r = q.toRotationMatrix();
    for (int j = 0; j < count; ++j) {
      if (w[j] <= 0) continue;
      const double s = h2k * w[j] / (1 + h2k * w[j]);
      p[j] += s * (c + r * (rest[j] - c0) - p[j]);
    }
  }

  void substep(double t, double h) {
    const SimParams& sp = env_.params();
    const HeadPose pose = env_.motion().pose(t + h);
    const double drag_h = sp.air_drag * h;
    for (const Strand& s : strands_) {
      Vector3d* x = &x_[s.begin];
      Vector3d* v = &v_[s.begin];
      Vector3d* p = &p_[s.begin];
      const Vector3d* rest = &rest_local_[s.begin];
      const double* w = &w_[s.begin];
      const double* m = &mass_[s.begin];
      const double* len = &length_[s.begin];
      Quaterniond* rot = &window_rot_[s.window_begin];
      const int n = s.n;

      // 1. Root follows the head; the others predict under gravity and drag.
      p[0] = pose.to_world(rest[0]);
      for (int i = 1; i < n; ++i) {
        Vector3d vi = v[i] + h * sp.gravity;
        if (sp.air_drag > 0) vi = (vi + drag_h * env_.wind(t, x[i])) / (1 + drag_h);
        p[i] = x[i] + h * vi;
      }

      // 2. Root clamp, shape matching, stretch.
      const double h2 = h * h;
      Vector3d clamp[kWindow];
      const int clamped = s.root_k > 0 ? std::min(n, kWindow) : 0;
      for (int i = 1; i < clamped; ++i) clamp[i] = pose.to_world(rest[i]);
      for (int it = 0; it < sp.iterations; ++it) {
        for (int i = 1; i < clamped; ++i) {
          const double f = h2 * s.root_k * w[i] / (1 + h2 * s.root_k * w[i]);
          p[i] += f * (clamp[i] - p[i]);
        }
        if (s.bend_k > 0 && n >= 3)
          for (int k = 0; k < s.windows; ++k)
            match_window(p + k, rest + k, m + k, w + k, std::min(kWindow, n - k), rot[k],
                         h2 * s.bend_k);
        for (int i = 0; i + 1 < n; ++i) {
          const Vector3d d = p[i + 1] - p[i];
          const double l = d.norm();
          const double wsum = w[i] + w[i + 1];
          if (l < 1e-12 || wsum <= 0) continue;
          const Vector3d corr = ((l - len[i]) / (l * wsum)) * d;
          p[i] += w[i] * corr;
          p[i + 1] -= w[i + 1] * corr;
        }
      }

      // 3. Follow the leader, root to tip: each sample goes to its rest distance from its
      // (already placed) parent, and if that is inside the head's margin it slides out along the
      // signed-distance gradient and back onto the sphere around the parent. Lengths stay exact
      // and no sample is left inside (colliding before the pass let the pass pull samples back
      // in: 2.7 mm deep under `shake`).
      Vector3d* d = &dv_[s.begin];
      d[0].setZero();
      for (int i = 1; i < n; ++i) {
        const Vector3d e = p[i] - p[i - 1];
        const double l = e.norm();
        Vector3d fixed = l > 1e-12 ? Vector3d(p[i - 1] + (len[i - 1] / l) * e)
                                   : pose.to_world(rest[i]) - pose.to_world(rest[i - 1]) + p[i - 1];
        if (sp.collision)
          for (int k = 0; k < 3; ++k) {
            Vector3d normal;
            const double dist = env_.distance(fixed, pose, &normal);
            if (dist >= sp.collision_margin) break;
            const Vector3d out = fixed + (sp.collision_margin - dist) * normal - p[i - 1];
            fixed = p[i - 1] + (len[i - 1] / out.norm()) * out;
          }
        d[i] = fixed - p[i];
        p[i] = fixed;
      }

      // 4. Velocities with Mueller's correction, then internal damping of relative motion.
      v[0] = (p[0] - x[0]) / h;
      for (int i = 1; i < n; ++i) {
        v[i] = (p[i] - x[i]) / h;
        if (i + 1 < n) v[i] -= kFtlDamping * d[i + 1] / h;
      }
      if (sp.damping > 0 && n >= 3) {
        const double a = std::min(1.0, sp.damping * h);
        // Targets from the old velocities (Jacobi, kept in d); a linear velocity field, such as
        // a rigid swing about the root, is left alone, including at the tip.
        for (int i = 0; i < n; ++i) d[i] = v[i];
        for (int i = 1; i < n; ++i) {
          const Vector3d target =
              i + 1 < n ? Vector3d(0.5 * (d[i - 1] + d[i + 1])) : Vector3d(2 * d[i - 1] - d[i - 2]);
          v[i] += a * (target - d[i]);
        }
      }
      for (int i = 0; i < n; ++i) {
        x[i] = p[i];
        max_speed_ = std::max(max_speed_, v[i].norm());
        if (!p[i].allFinite()) max_speed_ = INFINITY;
      }
    }
  }
};

}  // namespace

std::unique_ptr<StrandSolver> make_dftl_solver(const Environment& env,
                                               const std::vector<Polyline>& rest) {
  return std::make_unique<DftlSolver>(env, rest);
}

}  // namespace wisp::sim
