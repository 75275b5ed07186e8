// Fur tufts: roots, rest directions, per-tuft springs and projection (see fur.hpp).
#include "sim/fur.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/rng.hpp"
#include "sim/solver.hpp"

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

// n directions of a Fibonacci lattice (even spacing on the sphere), each jittered by up to a
// quarter of the spacing, in the region.
std::vector<Vector3d> lattice(int n, const FurParams& f) {
  Rng rng(f.seed);
  const double golden = M_PI * (3 - std::sqrt(5.0)), jitter = std::sqrt(4 * M_PI / n) / 4;
  std::vector<Vector3d> out;
  for (int i = 0; i < n; ++i) {
    const double y = 1 - (i + 0.5) * 2 / n, r = std::sqrt(std::max(0.0, 1 - y * y));
    Vector3d d(r * std::cos(golden * i), y, r * std::sin(golden * i));
    d = (d + jitter * Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)))
            .normalized();
    if (in_fur_region(d, f)) out.push_back(d);
  }
  return out;
}

// Unit tangent of the surface at normal n towards d (any tangent if d is along n).
Vector3d tangent_towards(const Vector3d& n, const Vector3d& d) {
  Vector3d t = d - d.dot(n) * n;
  if (t.norm() < 1e-9) t = n.unitOrthogonal();
  return t.normalized();
}

// The tip put back at `length` from the root and at least `lift` (cosine) off the skin.
Vector3d constrain(const Vector3d& root, const Vector3d& normal, const Vector3d& tip,
                   double length) {
  constexpr double kLift = 0.15;
  Vector3d d = tip - root;
  if (d.norm() < 1e-12) d = normal;
  d.normalize();
  const double up = d.dot(normal);
  if (up < kLift) {
    const Vector3d t = tangent_towards(normal, d);
    d = kLift * normal + std::sqrt(1 - kLift * kLift) * t;
  }
  return root + length * d;
}

}  // namespace

bool in_fur_region(const Vector3d& d, const FurParams& f) {
  const double from_crown = std::acos(std::clamp(d.y(), -1.0, 1.0)) * 180 / M_PI;
  const double from_face = std::acos(std::clamp(d.z(), -1.0, 1.0)) * 180 / M_PI;
  return from_crown <= f.scalp_angle_deg && from_face >= f.face_angle_deg;
}

Vector3d fur_direction(const Vector3d& n, const FurParams& f) {
  if (f.comb_direction.norm() < 1e-12) return n;
  return (n + f.comb * tangent_towards(n, f.comb_direction.normalized())).normalized();
}

void validate(const FurParams& f) {
  require(f.count >= 0 && f.count <= 200000, "count", "must be in [0, 200000]");
  require(f.length > 0 && f.length <= 0.2, "length", "must be in (0, 0.2] m");
  require(f.length_variation >= 0 && f.length_variation < 1, "length_variation",
          "must be in [0, 1)");
  require(f.strands >= 1 && f.strands <= 32, "strands", "must be in [1, 32]");
  require(f.clump_radius >= 0 && f.clump_radius <= 4, "clump_radius", "must be in [0, 4]");
  require(f.clump >= 0 && f.clump <= 1, "clump", "must be in [0, 1]");
  require(f.scalp_angle_deg > 0 && f.scalp_angle_deg <= 180, "scalp_angle_deg",
          "must be in (0, 180]");
  require(f.face_angle_deg >= 0 && f.face_angle_deg < 180, "face_angle_deg", "must be in [0, 180)");
  require(f.comb_direction.allFinite() && f.comb_direction.cwiseAbs().maxCoeff() <= 1e6,
          "comb_direction", "must be finite, components in [-1e6, 1e6]");
  require(f.comb >= 0 && f.comb <= 20, "comb", "must be in [0, 20]");
  require(f.stiffness > 0 && f.stiffness <= 1e6, "stiffness", "must be in (0, 1e6] 1/s^2");
  require(f.damping >= 0 && f.damping <= 1e4, "damping", "must be in [0, 1e4] 1/s");
  require(f.drag >= 0 && f.drag <= 1e4, "drag", "must be in [0, 1e4] 1/s");
  require(f.step_rate >= 10 && f.step_rate <= 1e5, "step_rate", "must be in [10, 1e5] per second");
  // The explicit spring step is stable for sqrt(stiffness) / step_rate well below 2.
  require(std::sqrt(f.stiffness) / f.step_rate <= 0.5, "step_rate",
          "too low for the stiffness: needs sqrt(stiffness) / step_rate <= 0.5");
}

FurModel make_fur(const FurParams& f, const HeadShape& head) {
  validate(f);
  FurModel model;
  if (f.count == 0) return model;
  // The lattice covers the whole sphere; scale it so that about `count` land in the region.
  std::vector<Vector3d> dirs = lattice(f.count, f);
  if (dirs.empty())
    throw std::invalid_argument("scalp_angle_deg / face_angle_deg: the fur's region is empty");
  const int n = int(std::min<double>(4e6, std::ceil(double(f.count) * f.count / dirs.size())));
  dirs = lattice(n, f);
  if (int(dirs.size()) > f.count) dirs.resize(f.count);

  double area_sum = 0;  // the head's area by the directions' share, for the spacing
  Rng rng(f.seed ^ 0x5eedf00dull);
  for (const Vector3d& d : dirs) {
    FurTuftRest t;
    t.root = head.surface_point(d);
    head.distance(t.root, &t.normal);
    t.normal.normalize();
    area_sum += t.root.squaredNorm();
    t.direction = fur_direction(t.normal, f);
    t.length = f.length * (1 + f.length_variation * rng.uniform(-1, 1));
    t.variance = rng.uniform(0.8, 1.0);
    model.tufts.push_back(std::move(t));
  }
  // Each direction stands for 4 pi / n steradians of the sphere around the centre.
  model.spacing = std::sqrt(4 * M_PI / n * area_sum / dirs.size());
  for (FurTuftRest& t : model.tufts) {
    const Vector3d u = t.normal.unitOrthogonal(), v = t.normal.cross(u);
    for (int s = 0; s < f.strands; ++s) {
      // A sunflower disc of strand roots, turned per tuft.
      const double r = f.strands == 1 ? 0 : std::sqrt((s + 0.5) / f.strands);
      const double a = s * 2.39996 + rng.uniform(0, 2 * M_PI);
      const Vector3d off = f.clump_radius * model.spacing * r * (std::cos(a) * u + std::sin(a) * v);
      FurStrand st;
      st.root_offset = off;
      st.tip_offset = (1 - f.clump) * off;
      st.length_scale = 1 + 0.5 * f.length_variation * rng.uniform(-1, 1);
      t.strands.push_back(st);
    }
  }
  return model;
}

FurMotion simulate_fur(const FurModel& model, const FurParams& f, const Environment& env,
                       const std::vector<double>& times, double settle) {
  FurMotion out;
  if (model.tufts.empty() || times.empty()) {
    out.tips.assign(times.size(), {});
    return out;
  }
  const size_t n = model.tufts.size();
  const double dt = 1.0 / f.step_rate;
  const Vector3d g = env.params().gravity;
  std::vector<Vector3d> tip(n), vel(n, Vector3d::Zero()), root(n), rest(n), normal(n), wind(n);
  // The wind at each root, sampled once per frame: its gusts change over seconds, and sampling it
  // every step cost most of the springs' time.
  const auto sample_wind = [&](double t) {
    for (size_t i = 0; i < n; ++i) wind[i] = env.wind(t, root[i]);
  };
  const auto pose_at = [&](double t) {
    const HeadPose p = env.motion().pose(t);
    for (size_t i = 0; i < n; ++i) {
      const FurTuftRest& r = model.tufts[i];
      root[i] = p.to_world(r.root);
      normal[i] = p.rotation * r.normal;
      rest[i] = root[i] + r.length * (p.rotation * r.direction);
    }
  };
  // One step at time t: semi-implicit Euler on the spring, then the length and skin constraints;
  // the velocity is the constrained displacement over the step (position-based), so the
  // constraints do not pump energy.
  std::vector<Vector3d> prev_root(n);
  const auto step = [&](double t, bool moving) {
    prev_root = root;
    if (moving) pose_at(t + dt);
    for (size_t i = 0; i < n; ++i) {
      const Vector3d root_vel = (root[i] - prev_root[i]) / dt;
      const Vector3d a = f.stiffness * (rest[i] - tip[i]) - f.damping * (vel[i] - root_vel) + g +
                         f.drag * (wind[i] - vel[i]);
      const Vector3d v = vel[i] + dt * a;
      const Vector3d p = constrain(root[i], normal[i], tip[i] + dt * v, model.tufts[i].length);
      vel[i] = (p - tip[i]) / dt;
      tip[i] = p;
    }
  };
  pose_at(times.front());
  sample_wind(times.front());
  tip = rest;
  const long settle_steps = std::lround(settle * f.step_rate);
  for (long s = 0; s < settle_steps; ++s) step(times.front(), false);
  double t = times.front();
  for (double frame_time : times) {
    sample_wind(t);
    // Whole steps up to the frame, then the frame at its own time.
    while (t + dt <= frame_time + 1e-12) {
      step(t, true);
      t += dt;
    }
    out.tips.push_back(tip);
  }
  return out;
}

ProjectedFur project_fur(const FurModel& model, const std::vector<Eigen::Vector3d>& tips,
                         const HeadPose& pose, const Camera& camera,
                         const Eigen::Vector3d& light_dir, double max_facing) {
  ProjectedFur out;
  out.focal_px = camera.focal_px;
  out.eye = camera.eye;
  out.light_dir = light_dir.norm() > 0 ? Vector3d(light_dir.normalized()) : Vector3d::UnitZ();
  for (size_t i = 0; i < model.tufts.size() && i < tips.size(); ++i) {
    const FurTuftRest& r = model.tufts[i];
    ProjectedTuft t;
    t.id = int(i);
    t.root = pose.to_world(r.root);
    t.normal = pose.rotation * r.normal;
    const Vector3d to_eye = camera.eye - t.root;
    if (camera.forward.dot(-to_eye) < 1e-3) continue;  // behind the eye
    t.facing = t.normal.dot(to_eye.normalized());
    if (std::abs(t.facing) >= max_facing) continue;
    const Vector3d reach = tips[i] - t.root;
    t.tangent = reach.norm() > 1e-12 ? Vector3d(reach.normalized()) : t.normal;
    const Vector3d half = 0.5 * r.length * (pose.rotation * r.direction);
    t.depth = to_eye.norm();
    t.variance = r.variance;
    for (const FurStrand& s : r.strands) {
      const Vector3d p0 = t.root + pose.rotation * s.root_offset;
      const Vector3d p2 = t.root + s.length_scale * reach + pose.rotation * s.tip_offset;
      const Vector3d p1 = p0 + s.length_scale * half;
      double d0 = 0;
      t.strand_points.push_back(camera.project(p0, &d0));
      t.strand_points.push_back(camera.project(p1));
      t.strand_points.push_back(camera.project(p2));
      t.strand_depth.push_back(d0);
    }
    out.tufts.push_back(std::move(t));
  }
  return out;
}

}  // namespace wisp::sim
