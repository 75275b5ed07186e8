// The strand solvers behind sim.model, and the environment they share: the moving head (pose,
// signed distance), the body under it, gravity and gusty wind. Each solver owns its state and
// advances every guide by one fixed physics step; simulate.cpp drives them and samples frames.
//  - dftl: our Dynamic Follow-The-Leader solver (sim/solver_dftl.cpp), the default;
//  - featherstone: one btMultiBody chain per guide (sim/solver_featherstone.cpp);
//  - rope: Bullet soft-body ropes, a baseline for comparison only (sim/solver_rope.cpp).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "sim/head.hpp"
#include "sim/motion.hpp"
#include "sim/simulate.hpp"

namespace wisp::sim {

class Environment {
 public:
  explicit Environment(const SimSetup& setup);

  const HeadShape& head() const { return head_; }
  const HeadMotion& motion() const { return motion_; }
  const SimParams& params() const { return params_; }

  // Wind velocity at world point x and time t: the mean wind plus gusts that travel along it.
  Eigen::Vector3d wind(double t, const Eigen::Vector3d& x) const;

  // Signed distance of world point x to the head, neck, torso and arms (the nearest), with
  // the outward unit normal in world space.
  double distance(const Eigen::Vector3d& x, const HeadPose& pose, Eigen::Vector3d* normal) const;

  // Moves x out to at least `margin` from the head and body. Returns true if it moved.
  bool push_out(Eigen::Vector3d& x, const HeadPose& pose, double margin) const;

 private:
  HeadShape head_;
  HeadMotion motion_;
  std::optional<BodyShape> body_;
  // The body posed for the last pose asked about: the solvers ask for one pose many times.
  mutable HeadPose posed_pose_;
  mutable std::optional<BodyShape::Posed> posed_;
  SimParams params_;
  double gust_phase_[3], gust_rate_[3];
};

class StrandSolver {
 public:
  virtual ~StrandSolver() = default;
  // Advances every guide from time t to t + dt.
  virtual void step(double t, double dt) = 0;
  // World positions of every guide, root first.
  virtual void positions(std::vector<Polyline>& out) const = 0;
  // Speed of the fastest sample during the last step (m/s); non-finite if the state is broken.
  virtual double max_speed() const = 0;
};

// `rest` in head-local metres; the solvers start from the rest shape at motion time 0.
std::unique_ptr<StrandSolver> make_dftl_solver(const Environment& env,
                                               const std::vector<Polyline>& rest);
std::unique_ptr<StrandSolver> make_featherstone_solver(const Environment& env,
                                                       const std::vector<Polyline>& rest);
std::unique_ptr<StrandSolver> make_rope_solver(const Environment& env,
                                               const std::vector<Polyline>& rest);

}  // namespace wisp::sim
