// The physics bar of the simulator (default model "dftl" unless a test says otherwise):
// inextensibility under violent motion, rest-shape hold, the compound-pendulum period, monotonic
// energy decay with drag, head collisions, determinism and the blow-up error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/head.hpp"
#include "sim/simulate.hpp"
#include "tests/sim/sim_fixtures.hpp"

using namespace wisp::sim;
using Eigen::Vector3d;

namespace {

double max_displacement(const StrandFrame& a, const StrandFrame& b) {
  double worst = 0;
  for (std::size_t s = 0; s < a.strands.size(); ++s)
    for (std::size_t i = 0; i < a.strands[s].size(); ++i)
      worst = std::max(worst, (a.strands[s][i] - b.strands[s][i]).norm());
  return worst;
}

// Times where x(t) crosses `level` upwards, linearly interpolated between frames.
std::vector<double> upward_crossings(const std::vector<double>& t, const std::vector<double>& x,
                                     double level) {
  std::vector<double> out;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < level && x[i] >= level)
      out.push_back(t[i - 1] + (t[i] - t[i - 1]) * (level - x[i - 1]) / (x[i] - x[i - 1]));
  return out;
}

// Kinetic + potential energy of a strand at frame f (central-difference velocities), with the
// sample masses of the simulator (half of each adjacent segment).
double strand_energy(const Animation& a, int f, double density, double g) {
  const Polyline& p = a.frames[f].strands[0];
  const Polyline& prev = a.frames[f - 1].strands[0];
  const Polyline& next = a.frames[f + 1].strands[0];
  const double dt = a.frames[f + 1].time - a.frames[f - 1].time;
  double e = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double l_prev = (p[i] - p[i - 1]).norm();
    const double l_next = i + 1 < p.size() ? (p[i + 1] - p[i]).norm() : 0.0;
    const double m = density * 0.5 * (l_prev + l_next);
    const Vector3d v = (next[i] - prev[i]) / dt;
    e += m * (0.5 * v.squaredNorm() + g * p[i].y());
  }
  return e;
}

}  // namespace

TEST_CASE("strands stay inextensible over 5 s of violent shake", "[sim][physics]") {
  SimSetup setup = test::small_head(60, 24, HairCurl::Wavy, MotionPreset::Shake, 5.0);
  const Animation anim = simulate(setup);
  double worst = 0;
  for (const StrandFrame& f : anim.frames) worst = std::max(worst, max_stretch(f, setup.rest));
  std::printf("[measured] dftl max relative stretch over 5 s of shake: %.3g\n", worst);
  CHECK(worst <= 1e-4);
  // The motion was violent: tips really moved relative to the head.
  double swing = 0;
  for (const StrandFrame& f : anim.frames)
    for (std::size_t s = 0; s < f.strands.size(); ++s)
      swing = std::max(swing, (f.head.to_local(f.strands[s].back()) - setup.rest[s].back()).norm());
  CHECK(swing > 0.05);
}

TEST_CASE("featherstone chains are inextensible too", "[sim][physics]") {
  SimSetup setup = test::small_head(10, 16, HairCurl::Wavy, MotionPreset::Shake, 2.0);
  setup.sim.model = SimModel::Featherstone;
  setup.sim.substeps = 80;  // explicit joint springs need small steps: see docs/sim.md
  const Animation anim = simulate(setup);
  double worst = 0;
  for (const StrandFrame& f : anim.frames) worst = std::max(worst, max_stretch(f, setup.rest));
  std::printf("[measured] featherstone max relative stretch over 2 s of shake: %.3g\n", worst);
  CHECK(worst <= 1e-4);
}

TEST_CASE("curly hair holds its rest shape with gravity off and no motion", "[sim][physics]") {
  SimSetup setup = test::small_head(40, 24, HairCurl::Curly, MotionPreset::None, 5.0);
  setup.sim.gravity.setZero();
  const Animation anim = simulate(setup);
  StrandFrame rest = anim.frames.front();
  for (std::size_t s = 0; s < rest.strands.size(); ++s)
    for (std::size_t i = 0; i < rest.strands[s].size(); ++i)
      rest.strands[s][i] = rest.head.to_world(setup.rest[s][i]);
  const double moved = max_displacement(anim.frames.back(), rest);
  std::printf("[measured] curly rest hold, gravity off, 5 s: max displacement %.3g m\n", moved);
  CHECK(moved <= 1e-3 * HairParams{}.length);  // 1e-3 of the strand length
}

TEST_CASE("stiff curls keep their curl under gravity", "[sim][physics]") {
  HeadParams head;
  HairParams hair;
  hair.count = 30;
  hair.segments = 40;
  hair.style = HairCurl::Curly;
  hair.frequency = 20;  // turns per metre: 6 turns on 0.3 m
  hair.amplitude = 0.01;
  hair.length_variation = 0;
  MotionParams motion;
  motion.preset = MotionPreset::None;
  motion.duration = 3.0;
  SimParams sim;
  sim.bend_stiffness = 2e-3;
  const SimSetup setup = make_setup(head, hair, motion, sim);
  const Animation anim = simulate(setup);
  // Half a turn in samples: 40 segments over 6 turns.
  const int half = static_cast<int>(std::lround(40.0 / (2 * 0.3 * 20)));
  double rest_amp = 0, sim_amp = 0;
  for (std::size_t s = 0; s < setup.rest.size(); ++s) {
    rest_amp += curl_amplitude(setup.rest[s], half);
    sim_amp += curl_amplitude(anim.frames.back().strands[s], half);
  }
  std::printf("[measured] curl amplitude after 3 s under gravity: %.4g m vs rest %.4g m\n",
              sim_amp / setup.rest.size(), rest_amp / setup.rest.size());
  CHECK(sim_amp == Approx(rest_amp).epsilon(0.2));
  // And gravity did act: the strands sagged.
  double sag = 0;
  for (std::size_t s = 0; s < setup.rest.size(); ++s)
    sag = std::max(sag, (anim.frames.back().strands[s].back() - setup.rest[s].back()).norm());
  CHECK(sag > 1e-3);
}

TEST_CASE("a stiff strand swings with the period of a compound pendulum", "[sim][physics]") {
  const double L = 0.3, g = 9.81;
  SimSetup setup = test::single_strand(L, 24, 10.0, 3.0);
  setup.sim.bend_stiffness = 1.0;
  setup.sim.root_stiffness = 0;  // free pivot at the root
  setup.sim.fps = 240;
  setup.sim.step_rate = 240;
  const Animation anim = simulate(setup);
  std::vector<double> t, x;
  for (const StrandFrame& f : anim.frames) {
    t.push_back(f.time);
    x.push_back(f.strands[0].back().x());
  }
  const std::vector<double> up = upward_crossings(t, x, 0.0);
  REQUIRE(up.size() >= 3);
  const double period = (up.back() - up.front()) / (up.size() - 1);
  const double expected = 2 * M_PI * std::sqrt(2 * L / (3 * g));
  std::printf("[measured] pendulum period %.4f s, compound pendulum %.4f s (error %.2f %%)\n",
              period, expected, 100 * (period / expected - 1));
  CHECK(period == Approx(expected).epsilon(0.05));
}

TEST_CASE("with drag, a swinging strand's energy decays monotonically", "[sim][physics]") {
  SimSetup setup = test::single_strand(0.3, 24, 30.0, 3.0);
  setup.sim.bend_stiffness = 1.0;
  setup.sim.root_stiffness = 0;
  setup.sim.air_drag = 0.5;
  setup.sim.fps = 120;
  setup.sim.step_rate = 240;
  const Animation anim = simulate(setup);
  std::vector<double> e;
  for (int f = 1; f + 1 < static_cast<int>(anim.frames.size()); ++f)
    e.push_back(strand_energy(anim, f, setup.sim.density, 9.81));
  const double span = e.front() - *std::min_element(e.begin(), e.end());
  REQUIRE(span > 0);
  int rises = 0;
  double worst_rise = 0;
  for (std::size_t i = 1; i < e.size(); ++i)
    if (e[i] > e[i - 1]) {
      ++rises;
      worst_rise = std::max(worst_rise, (e[i] - e[i - 1]) / span);
    }
  std::printf("[measured] energy: %zu samples, lost %.3g J, %d rises (worst %.2g of the loss)\n",
              e.size(), span, rises, worst_rise);
  CHECK(worst_rise < 1e-3);  // finite-difference velocities: tolerate rounding-level wiggles
  CHECK(e.back() < e.front());
}

TEST_CASE("no strand sample ends inside the head by more than the margin", "[sim][physics]") {
  for (const SimModel model : {SimModel::Dftl, SimModel::Featherstone}) {
    INFO(choice_name(model));
    const bool featherstone = model == SimModel::Featherstone;
    SimSetup setup = test::small_head(featherstone ? 10 : 100, featherstone ? 16 : 24,
                                      HairCurl::Wavy, MotionPreset::Shake, 2.0);
    setup.sim.model = model;
    if (featherstone) setup.sim.substeps = 80;
    const Animation anim = simulate(setup);
    const HeadShape head(setup.head);
    double deepest = 1;
    for (const StrandFrame& f : anim.frames)
      for (const Polyline& s : f.strands)
        for (std::size_t i = 1; i < s.size(); ++i)
          deepest = std::min(deepest, head.distance(f.head.to_local(s[i])));
    std::printf("[measured] %s: smallest signed distance to the head %.3g m (margin %.3g)\n",
                choice_name(model), deepest, setup.sim.collision_margin);
    CHECK(deepest >= -setup.sim.collision_margin);
    if (!featherstone) CHECK(deepest >= 0);  // dftl: not even inside the surface
  }
}

TEST_CASE("two runs of the same scene give identical animations", "[sim][physics]") {
  SimSetup setup = test::small_head(20, 12, HairCurl::Wavy, MotionPreset::Walk, 1.0);
  setup.sim.wind.velocity = Vector3d(0.5, 0, 0);
  setup.sim.wind.gust = 1.0;
  const Animation a = simulate(setup), b = simulate(setup);
  REQUIRE(a.frames.size() == b.frames.size());
  bool same = true;
  for (std::size_t f = 0; f < a.frames.size(); ++f)
    for (std::size_t s = 0; s < a.frames[f].strands.size(); ++s)
      same = same && a.frames[f].strands[s] == b.frames[f].strands[s];
  CHECK(same);
}

TEST_CASE("a stiffness that blows up the integrator is a clear error with the frame",
          "[sim][physics]") {
  SimSetup setup = test::small_head(5, 16, HairCurl::Wavy, MotionPreset::Shake, 2.0);
  setup.sim.model = SimModel::Featherstone;
  setup.sim.bend_stiffness = 50.0;
  setup.sim.substeps = 1;
  try {
    simulate(setup);
    FAIL("expected the simulation to blow up");
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    INFO(msg);
    CHECK(msg.find("blew up at frame") != std::string::npos);
    CHECK(msg.find("sim.bend_stiffness") != std::string::npos);
  }
}

TEST_CASE("bad simulation parameters are rejected naming the field", "[sim]") {
  SimSetup setup = test::single_strand(0.3, 4, 0, 1.0);
  setup.sim.step_rate = -1;
  CHECK_THROWS_WITH(simulate(setup), Catch::Contains("sim.step_rate"));
  setup = test::single_strand(0.3, 4, 0, 1.0);
  setup.sim.bend_stiffness = -1;
  CHECK_THROWS_WITH(simulate(setup), Catch::Contains("sim.bend_stiffness"));
  setup = test::single_strand(0.3, 4, 0, 1.0);
  setup.rest[0][2] = setup.rest[0][1];
  CHECK_THROWS_WITH(simulate(setup), Catch::Contains("zero length"));
}
