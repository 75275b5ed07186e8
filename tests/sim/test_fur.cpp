// Fur tufts (sim/fur.hpp): roots cover the region evenly and nowhere else; a tuft at rest leans
// with its comb, sags under gravity by about g / stiffness and leans downwind; tufts keep their
// length and stay off the skin while the head turns fast; the springs are step-size independent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "sim/fur.hpp"
#include "sim/simulate.hpp"
#include "sim/solver.hpp"

using namespace wisp::sim;
using Eigen::Vector3d;

namespace {

HeadShape sphere_head(double r = 0.09) {
  HeadGeometry g;
  g.radii = Vector3d(r, r, r);
  return HeadShape(g);
}

Environment environment(const MotionParams& motion, const Vector3d& wind = Vector3d::Zero()) {
  HeadParams head;
  head.radii = Vector3d(0.09, 0.09, 0.09);
  SimParams sim;
  sim.wind.velocity = wind;
  return Environment(make_base_setup(head, motion, sim));
}

MotionParams still() {
  MotionParams m;
  m.preset = MotionPreset::None;
  m.duration = 1;
  return m;
}

std::vector<double> frame_times(double duration, double fps = 24) {
  std::vector<double> t;
  for (int k = 0; k <= int(duration * fps); ++k) t.push_back(k / fps);
  return t;
}

}  // namespace

TEST_CASE("fur roots: about `count`, in the region only, on the head", "[sim][fur]") {
  FurParams f;
  f.count = 2000;
  f.face_angle_deg = 50;
  const HeadShape head = sphere_head();
  const FurModel m = make_fur(f, head);
  CHECK(m.tufts.size() >= 1900);
  CHECK(m.tufts.size() <= 2000);
  for (const FurTuftRest& t : m.tufts) {
    REQUIRE(std::abs(head.distance(t.root)) < 1e-6);
    REQUIRE(in_fur_region(t.root.normalized(), f));
    REQUIRE(t.strands.size() == size_t(f.strands));
  }
  // Even spacing: the nearest neighbour of every root is within a factor 2.5 of the mean spacing.
  int crowded = 0;
  for (size_t i = 0; i < m.tufts.size(); i += 7) {
    double nearest = INFINITY;
    for (size_t j = 0; j < m.tufts.size(); ++j)
      if (j != i) nearest = std::min(nearest, (m.tufts[i].root - m.tufts[j].root).norm());
    crowded += nearest < m.spacing / 2.5 || nearest > 2.5 * m.spacing;
  }
  CHECK(crowded == 0);
  f.count = 0;
  CHECK(make_fur(f, head).tufts.empty());
}

TEST_CASE("fur at rest: combed, sagging by g / stiffness, leaning downwind", "[sim][fur]") {
  FurParams f;
  f.count = 400;
  f.comb = 0;  // standing straight up from the skin
  const FurModel m = make_fur(f, sphere_head());
  const std::vector<double> times = frame_times(0.5);
  const FurMotion calm = simulate_fur(m, f, environment(still()), times);
  // A tuft on the side of the head (normal horizontal): gravity pulls its tip down by about
  // g / stiffness (less the part that the length constraint takes up).
  size_t side = 0;
  for (size_t i = 0; i < m.tufts.size(); ++i)
    if (std::abs(m.tufts[i].normal.y()) < std::abs(m.tufts[side].normal.y())) side = i;
  const FurTuftRest& t = m.tufts[side];
  const Vector3d rest_tip = t.root + t.length * t.direction;
  const Vector3d sag = calm.tips.back()[side] - rest_tip;
  CHECK(sag.y() < -0.5 * 9.81 / f.stiffness);
  CHECK(sag.y() > -1.5 * 9.81 / f.stiffness);
  CHECK((calm.tips.back()[side] - t.root).norm() == Approx(t.length).epsilon(1e-9));

  // Wind along +x leans the tufts on top of the head towards +x.
  const FurMotion windy = simulate_fur(m, f, environment(still(), Vector3d(3, 0, 0)), times);
  size_t top = 0;
  for (size_t i = 0; i < m.tufts.size(); ++i)
    if (m.tufts[i].normal.y() > m.tufts[top].normal.y()) top = i;
  const double lean = (windy.tips.back()[top] - calm.tips.back()[top]).x();
  CHECK(lean > 0.2 * m.tufts[top].length);
}

TEST_CASE("fur on a fast turn: length kept, off the skin, lagging; step-size independent",
          "[sim][fur]") {
  FurParams f;
  f.count = 300;
  MotionParams shake;
  shake.preset = MotionPreset::Shake;
  shake.duration = 2;
  const Environment env = environment(shake);
  const HeadShape head = sphere_head();
  const FurModel m = make_fur(f, head);
  const std::vector<double> times = frame_times(2);
  const FurMotion a = simulate_fur(m, f, env, times);
  double max_lag = 0;
  for (size_t k = 0; k < times.size(); ++k) {
    const HeadPose pose = env.motion().pose(times[k]);
    for (size_t i = 0; i < m.tufts.size(); ++i) {
      const FurTuftRest& t = m.tufts[i];
      const Vector3d root = pose.to_world(t.root), n = pose.rotation * t.normal;
      const Vector3d d = a.tips[k][i] - root;
      REQUIRE(d.norm() == Approx(t.length).epsilon(1e-9));
      REQUIRE(d.normalized().dot(n) >= 0.15 - 1e-9);
      max_lag = std::max(max_lag,
                         (a.tips[k][i] - (root + t.length * (pose.rotation * t.direction))).norm());
    }
  }
  CHECK(max_lag > 0.1 * f.length);  // the head's motion moves the tufts

  // On an ordinary turn, twice the step rate gives the same motion within a small fraction of
  // the length (the shake above is violent enough to make any first-order step differ more).
  MotionParams turn;
  turn.preset = MotionPreset::Turn;
  turn.duration = 2;
  const Environment turning = environment(turn);
  const FurMotion c = simulate_fur(m, f, turning, times);
  FurParams fine = f;
  fine.step_rate = 2 * f.step_rate;
  const FurMotion b = simulate_fur(m, fine, turning, times);
  double worst = 0, moved = 0;
  for (size_t k = 0; k < times.size(); ++k)
    for (size_t i = 0; i < m.tufts.size(); ++i) {
      worst = std::max(worst, (c.tips[k][i] - b.tips[k][i]).norm());
      moved = std::max(moved, (c.tips[k][i] - c.tips[0][i]).norm());
    }
  CHECK(moved > f.length);
  CHECK(worst < 0.05 * f.length);
}

TEST_CASE("fur parameters out of range name their field", "[sim][fur]") {
  const auto error = [](FurParams f) {
    try {
      validate(f);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error(FurParams{}).empty());
  FurParams f;
  f.count = -1;
  CHECK(error(f).rfind("count:", 0) == 0);
  f = {};
  f.stiffness = 1e6;
  CHECK(error(f).rfind("step_rate: too low for the stiffness", 0) == 0);
  f = {};
  f.clump = 2;
  CHECK(error(f).rfind("clump:", 0) == 0);
}
