// The scenes shipped in data/scenes: each parses, simulates, and from its camera the hair sits on
// the head, in the frame; long-wind's gusts visibly move the hair.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/render/scene_setup.hpp"
#include "io/scene.hpp"
#include "sim/body.hpp"
#include "sim/camera.hpp"

namespace fs = std::filesystem;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

double cross2(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

bool in_triangle(const wisp::sim::ProjectedSurface& s, const Eigen::Vector3i& t,
                 const Vector2d& q) {
  const Vector2d p[3] = {s.pixel[t[0]], s.pixel[t[1]], s.pixel[t[2]]};
  const double a = cross2(p[1] - p[0], q - p[0]), b = cross2(p[2] - p[1], q - p[1]),
               c = cross2(p[0] - p[2], q - p[2]);
  return (a <= 0 && b <= 0 && c <= 0) || (a >= 0 && b >= 0 && c >= 0);
}

fs::path scene_file(const char* name) {
  return fs::path(WISP_SOURCE_DIR) / "data/scenes" / name;
}

}  // namespace

TEST_CASE("every shipped scene simulates, and its hair sits on the head inside the frame",
          "[io][scenes]") {
  for (const char* name : {"default.json", "bob.json", "curly.json", "long-wind.json",
                           "sim_small.json", "dense.json"}) {
    INFO(name);
    wisp::io::Scene scene = wisp::io::load_scene(scene_file(name));
    scene.motion.duration = std::min(scene.motion.duration, 1.0);
    // The head keeps its pose after the last key, so a shortened keyed motion still works.
    scene.camera.width = scene.camera.height = 256;
    const wisp::sim::SimSetup setup = wisp::render::load_sim_setup(scene);
    const wisp::sim::Animation anim = wisp::sim::simulate(setup);
    wisp::sim::Projector projector(anim.head, scene.camera, wisp::render::projector_options(scene));
    const wisp::sim::BodyModel body(anim.head, wisp::render::body_params(scene));
    const wisp::sim::HeadShape head(anim.head);
    int samples = 0, outside_frame = 0, roots_off_head = 0;
    double deepest = 1;
    for (const wisp::sim::StrandFrame& f : anim.frames) {
      const wisp::sim::ProjectedFrame pf = projector.project(f);
      CHECK(pf.light_dir.isApprox(scene.light_dir));
      const bool check_roots = f.frame % 6 == 0;
      wisp::sim::ProjectedBody pb;
      if (check_roots) pb = body.project(f.head, projector.camera(), scene.light_dir);
      for (std::size_t s = 0; s < pf.strands.size(); ++s) {
        const wisp::sim::ProjectedStrand& ps = pf.strands[s];
        for (std::size_t i = 0; i < ps.pixel.size(); ++i) {
          ++samples;
          const Vector2d& p = ps.pixel[i];
          outside_frame += p.x() < 0 || p.y() < 0 || p.x() > 256 || p.y() > 256;
          if (i > 0) deepest = std::min(deepest, head.distance(f.head.to_local(f.strands[s][i])));
        }
        if (check_roots) {
          bool on = false;
          for (const auto& surface : pb.surfaces)
            for (const auto& t : surface.triangles)
              on = on ||
                   (surface.part == wisp::sim::kBodyHead && in_triangle(surface, t, ps.pixel[0]));
          roots_off_head += !on;
        }
      }
    }
    std::printf(
        "[measured] %s: %zu frames, %zu guides, %.3f %% of samples outside the frame, "
        "deepest sample %.2g m from the head\n",
        name, anim.frames.size(), setup.rest.size(), 100.0 * outside_frame / samples, deepest);
    CHECK(outside_frame <= samples / 200);  // at most 0.5 % (a wind-blown tip may leave)
    CHECK(roots_off_head == 0);
    CHECK(deepest >= 0);  // no sample inside the head
  }
}

TEST_CASE("long-wind's gusts visibly move the hair", "[io][scenes]") {
  wisp::io::Scene scene = wisp::io::load_scene(scene_file("long-wind.json"));
  REQUIRE(scene.sim.wind.gust > 0);
  scene.motion.preset = wisp::sim::MotionPreset::None;  // only the wind moves the hair
  scene.motion.duration = 2.0;
  // Spread over time of the mean tip position along the wind.
  const auto tip_spread = [&](double gust) {
    scene.sim.wind.gust = gust;
    const wisp::sim::Animation anim = wisp::sim::simulate(wisp::render::load_sim_setup(scene));
    const Vector3d dir = scene.sim.wind.velocity.normalized();
    double sum = 0, sum2 = 0;
    for (const auto& f : anim.frames) {
      double m = 0;
      for (const auto& s : f.strands) m += s.back().dot(dir);
      m /= f.strands.size();
      sum += m;
      sum2 += m * m;
    }
    const double n = anim.frames.size();
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  };
  const double gusty = tip_spread(scene.sim.wind.gust), steady = tip_spread(0);
  std::printf(
      "[measured] long-wind: mean tip position along the wind varies by %.1f cm (std) with "
      "gusts, %.1f cm without\n",
      100 * gusty, 100 * steady);
  CHECK(gusty > 0.02);  // centimetres of sway
  CHECK(gusty > 4 * steady);
}
