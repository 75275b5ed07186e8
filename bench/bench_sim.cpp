// wisp-bench sim: our strand solver (dftl, the default) against Bullet's soft-body ropes and
// Bullet's Featherstone chains on the same roots, rest shapes and segment counts: 150 and 300
// procedural wavy guides x 24 links with head collision under the `shake` preset (Featherstone
// also at 16 links, the size of the prototype measured in issue 3). Reports seconds
// per simulated second (one core), max stretch and deepest head penetration per run, and the
// rope/dftl time ratio. Featherstone needs tiny steps for its explicit joint springs (see
// docs/sim.md), so it runs at 150 guides over a shorter shot unless --full is given.
// Usage: wisp-bench sim [--quick] [--full]
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/benches.hpp"
#include "diffusion/timer.hpp"
#include "sim/head.hpp"
#include "sim/simulate.hpp"

namespace wisp::bench {
namespace {

struct Run {
  sim::SimModel model = sim::SimModel::Dftl;
  std::string note;
  int guides = 0, links = 0, substeps = 0, iterations = 0;
  double duration = 0, wall = 0, stretch = 0, deepest = 0;
  std::string status = "ok";
};

Run run(sim::SimModel model, int guides, int links, double duration, int substeps, int iterations) {
  sim::HairParams hair;
  hair.count = guides;
  hair.segments = links;
  hair.style = sim::HairCurl::Wavy;
  sim::MotionParams motion;
  motion.preset = sim::MotionPreset::Shake;
  motion.duration = duration;
  sim::SimParams params;
  params.model = model;
  params.substeps = substeps;
  params.iterations = iterations;
  const sim::SimSetup setup = sim::make_setup(sim::HeadParams{}, hair, motion, params);
  Run r;
  r.model = model;
  r.guides = guides;
  r.links = hair.segments;
  r.substeps = substeps;
  r.iterations = iterations;
  r.duration = duration;
  std::fprintf(stderr, "sim: %s, %d guides, %.1f s of shake...\n", sim::choice_name(model), guides,
               duration);
  const auto start = diffusion::Clock::now();
  sim::Animation anim;
  try {
    anim = sim::simulate(setup);
  } catch (const std::exception& e) {
    r.status = e.what();
  }
  r.wall = diffusion::seconds_since(start);
  const sim::HeadShape head(setup.head);
  r.deepest = 1;
  for (const auto& f : anim.frames) {
    r.stretch = std::max(r.stretch, sim::max_stretch(f, setup.rest));
    for (const auto& s : f.strands)
      for (std::size_t i = 1; i < s.size(); ++i)
        r.deepest = std::min(r.deepest, head.distance(f.head.to_local(s[i])));
  }
  return r;
}

void print(const Run& r, bool last) {
  std::printf(
      "    {\"model\": \"%s\", \"guides\": %d, \"links\": %d, \"substeps\": %d, \"iterations\": "
      "%d, "
      "\"simulated_s\": %.2f, \"wall_s\": %.3f, \"s_per_simulated_s\": %.4f, \"realtime_factor\": "
      "%.2f, \"max_stretch\": %.3g, \"min_head_distance_m\": %.4f, \"status\": \"%s\"}%s\n",
      sim::choice_name(r.model), r.guides, r.links, r.substeps, r.iterations, r.duration, r.wall,
      r.wall / r.duration, r.duration / r.wall, r.stretch, r.deepest, r.status.c_str(),
      last ? "" : ",");
}

}  // namespace

int run_sim(const std::vector<std::string>& args) {
  const bool quick = std::find(args.begin(), args.end(), "--quick") != args.end();
  const bool full = std::find(args.begin(), args.end(), "--full") != args.end();
  const double shot = quick ? 1.5 : 4.0;
  std::vector<Run> runs;
  for (int guides : {150, 300}) {
    runs.push_back(run(sim::SimModel::Dftl, guides, 24, shot, 4, 1));
    runs.push_back(run(sim::SimModel::Rope, guides, 24, shot, 4, 4));
    runs.push_back(run(sim::SimModel::Rope, guides, 24, shot, 4, 20));
  }
  // Explicit joint springs at the default stiffness: 16 links need about 80 sub-steps of a
  // 120 Hz step; the stable step shrinks like the link length squared, so 24 links need ~200.
  runs.push_back(run(sim::SimModel::Featherstone, 150, 16, full ? shot : 1.5, 80, 1));
  runs.push_back(run(sim::SimModel::Featherstone, 150, 24, 1.5, 80, 1));
  if (full) runs.push_back(run(sim::SimModel::Featherstone, 150, 24, shot, 200, 1));

  std::printf(
      "{\n  \"benchmark\": \"sim\",\n  \"scene\": \"procedural wavy guides x 24 links, "
      "ellipsoid head with collision, shake preset (0.5 s still, then +-40 deg at 2.8 Hz), "
      "120 Hz steps\",\n  \"runs\": [\n");
  for (std::size_t i = 0; i < runs.size(); ++i) print(runs[i], i + 1 == runs.size());
  std::printf("  ],\n  \"ratios\": {");
  bool first = true;
  for (const Run& d : runs)
    for (const Run& r : runs)
      if (d.model == sim::SimModel::Dftl && r.model == sim::SimModel::Rope &&
          r.guides == d.guides) {
        std::printf("%s\n    \"rope_%d_iterations_over_dftl_%d_guides\": %.2f", first ? "" : ",",
                    r.iterations, d.guides, r.wall / d.wall);
        first = false;
      }
  std::printf("\n  }\n}\n");
  return 0;
}

}  // namespace wisp::bench
