// The simulation driver and the shared environment: see simulate.hpp and solver.hpp.
#include "sim/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "sim/rng.hpp"
#include "sim/solver.hpp"

namespace wisp::sim {

using Eigen::Vector3d;

Environment::Environment(const SimSetup& setup)
    : head_(setup.head), motion_(setup.motion), params_(setup.sim) {
  if (setup.body) body_.emplace(*setup.body);
  // Three incommensurate sines per gust signal, with seeded phases: smooth, never periodic
  // within a shot, identical for a given seed.
  Rng rng(params_.wind.seed);
  const double ratios[3] = {1.0, 2.31, 0.57};
  for (int k = 0; k < 3; ++k) {
    gust_phase_[k] = rng.uniform(0, 2 * M_PI);
    gust_rate_[k] = 2 * M_PI * params_.wind.gust_frequency * ratios[k] * rng.uniform(0.85, 1.15);
  }
}

Vector3d Environment::wind(double t, const Vector3d& x) const {
  const WindParams& w = params_.wind;
  if (w.gust == 0) return w.velocity;
  const double speed = w.velocity.norm();
  const Vector3d dir = speed > 1e-9 ? Vector3d(w.velocity / speed) : Vector3d::UnitX();
  const double tt = t - dir.dot(x) / std::max(speed, 1.0);  // gusts travel with the wind
  double g = 0;
  for (int k = 0; k < 3; ++k) g += std::sin(gust_rate_[k] * tt + gust_phase_[k]);
  return w.velocity + w.gust * (0.5 + g / 6.0) * dir;  // gust speed in [-0, 1] x w.gust
}

double Environment::distance(const Vector3d& x, const HeadPose& pose, Vector3d* normal) const {
  Vector3d n;
  double d = head_.distance(pose.to_local(x), &n);
  if (normal) *normal = pose.rotation * n;
  if (body_) {
    if (!posed_ || posed_pose_.position != pose.position ||
        posed_pose_.rotation.coeffs() != pose.rotation.coeffs()) {
      posed_ = body_->posed(pose);
      posed_pose_ = pose;
    }
    Vector3d nb;
    const double db = body_->distance(*posed_, x, &nb);
    if (db < d) {
      d = db;
      if (normal) *normal = nb;
    }
  }
  return d;
}

bool Environment::push_out(Vector3d& x, const HeadPose& pose, double margin) const {
  bool moved = false;
  for (int it = 0; it < 2; ++it) {  // the ellipsoid distance is first order: one more pass
    Vector3d n;
    const double d = distance(x, pose, &n);
    if (d >= margin) break;
    x += (margin - d) * n;
    moved = true;
  }
  return moved;
}

SimSetup make_base_setup(const HeadParams& head, const MotionParams& motion, const SimParams& sim,
                         const TriangleMesh& mesh) {
  validate_part(head, "head");
  validate_part(sim, "sim");
  SimSetup setup;
  setup.head.shape = head.shape;
  setup.head.radii = head.radii;
  setup.head.mesh = mesh;
  if (head.shoulders) {
    setup.body = body_params(head);  // the drawn neck, torso and arms
  }
  setup.motion = motion_keys(motion);
  setup.duration = motion.duration;
  setup.sim = sim;
  return setup;
}

SimSetup make_setup(const HeadParams& head, const HairParams& hair, const MotionParams& motion,
                    const SimParams& sim, const TriangleMesh& mesh) {
  SimSetup setup = make_base_setup(head, motion, sim, mesh);
  const HeadShape shape(setup.head);
  setup.rest = generate_hair(hair, shape, sim.collision_margin + 0.002);
  return setup;
}

double max_stretch(const StrandFrame& frame, const std::vector<Polyline>& rest) {
  double worst = 0;
  for (std::size_t s = 0; s < rest.size() && s < frame.strands.size(); ++s)
    for (std::size_t i = 1; i < rest[s].size(); ++i) {
      const double l0 = (rest[s][i] - rest[s][i - 1]).norm();
      const double l = (frame.strands[s][i] - frame.strands[s][i - 1]).norm();
      worst = std::max(worst, std::abs(l / l0 - 1));
    }
  return worst;
}

Animation simulate(const SimSetup& setup, const SimProgress& progress,
                   const SimFrameSink& on_frame) {
  validate_part(setup.sim, "sim");
  if (!(setup.duration > 0) || !std::isfinite(setup.duration))
    throw std::invalid_argument("motion.duration: must be a positive number of seconds");
  if (!setup.widths.empty()) {
    bool fits = setup.widths.size() == setup.rest.size();
    for (std::size_t s = 0; fits && s < setup.rest.size(); ++s)
      fits = setup.widths[s].size() == setup.rest[s].size();
    if (!fits) throw std::invalid_argument("hair: clump widths do not match the guides");
  }
  for (std::size_t s = 0; s < setup.rest.size(); ++s) {
    const Polyline& p = setup.rest[s];
    if (p.size() < 2)
      throw std::invalid_argument("hair: strand " + std::to_string(s) + " has fewer than 2 points");
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!p[i].allFinite())
        throw std::invalid_argument("hair: strand " + std::to_string(s) +
                                    " has a non-finite point");
      if (i > 0 && !((p[i] - p[i - 1]).norm() > 1e-9))
        throw std::invalid_argument("hair: strand " + std::to_string(s) +
                                    " has a segment of zero length");
    }
  }
  const Environment env(setup);
  const SimParams& sp = setup.sim;
  // No strands (a head that only grows fur, sim/fur.hpp): the frames carry the head's poses.
  std::unique_ptr<StrandSolver> solver =
      setup.rest.empty()                   ? nullptr
      : sp.model == SimModel::Featherstone ? make_featherstone_solver(env, setup.rest)
      : sp.model == SimModel::Rope         ? make_rope_solver(env, setup.rest)
                                           : make_dftl_solver(env, setup.rest);
  const double dt = 1.0 / sp.step_rate;
  const int frames = animation_frame_count(setup);
  Animation anim;
  anim.fps = sp.fps;
  anim.head = setup.head;
  anim.widths = setup.widths;
  anim.frames.reserve(frames);
  // The pre-roll runs steps at negative times, where the motion holds its first pose: the hair
  // settles from its rest shape before frame 0.
  long step = -std::lround(sp.preroll * sp.step_rate);
  for (int f = 0; f < frames; ++f) {
    // Frame f shows the state at the physics step nearest its time.
    const long target = std::lround(f / sp.fps * sp.step_rate);
    if (!solver) step = target;
    for (; step < target; ++step) {
      solver->step(step * dt, dt);
      const double v = solver->max_speed();
      if (!std::isfinite(v) || v > sp.max_speed) {
        char msg[320];
        std::snprintf(msg, sizeof msg,
                      "simulation blew up at frame %d (t = %.3f s): a strand sample moved at %g "
                      "m/s (sim.max_speed = %g); lower sim.bend_stiffness or raise "
                      "sim.step_rate / sim.substeps",
                      f, (step + 1) * dt, v, sp.max_speed);
        throw std::runtime_error(msg);
      }
    }
    StrandFrame frame;
    frame.frame = f;
    frame.time = step * dt;
    frame.head = env.motion().pose(frame.time);
    if (solver) solver->positions(frame.strands);
    if (on_frame) on_frame(frame);
    anim.frames.push_back(std::move(frame));
    if (progress) progress(f + 1, frames);
  }
  return anim;
}

int animation_frame_count(const SimSetup& setup) {
  return static_cast<int>(std::floor(setup.duration * setup.sim.fps + 1e-9)) + 1;
}

}  // namespace wisp::sim
