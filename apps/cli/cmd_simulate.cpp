// `wisp simulate scene.json -o anim.wsim`: runs the strand simulation of a scene and saves every
// frame's head pose and strands (io/anim_file.hpp), with a progress bar and a one-line summary.
#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli/commands.hpp"
#include "apps/render/progress.hpp"
#include "apps/render/scene_setup.hpp"
#include "diffusion/timer.hpp"
#include "io/anim_file.hpp"
#include "io/atomic_file.hpp"
#include "io/scene.hpp"
#include "sim/simulate.hpp"

namespace wisp::cli {

void add_command(CLI::App& app, const std::vector<std::string>&) {
  struct Options {
    std::string scene, output, model;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = add_subcommand(app, "simulate");
  cmd->add_option("scene", opt->scene, "scene JSON (docs/scene.md)")->required();
  cmd->add_option("-o,--output", opt->output, "animation file to write (.wsim)")->required();
  cmd->add_option("--model", opt->model, "override sim.model")
      ->check(CLI::IsMember(sim::choice_names<sim::SimModel>()));
  cmd->add_flag("-q,--quiet", opt->quiet, "no progress bar or summary");
  cmd->callback([opt]() {
    io::Scene scene = io::load_scene(opt->scene);
    io::check_writable(opt->output);
    if (!opt->model.empty()) scene.sim.model = *sim::parse_choice<sim::SimModel>(opt->model);
    const sim::SimSetup setup = render::load_sim_setup(scene);
    const auto start = diffusion::Clock::now();
    std::unique_ptr<render::ProgressBar> bar;
    if (!opt->quiet)
      bar = std::make_unique<render::ProgressBar>("simulate", sim::animation_frame_count(setup));
    const sim::Animation anim = sim::simulate(setup, [&](int done, int) {
      if (bar) bar->update(done);
    });
    if (bar) bar->finish();
    const double seconds = diffusion::seconds_since(start);
    io::write_animation(opt->output, anim);
    if (!opt->quiet) {
      double stretch = 0;
      for (const auto& f : anim.frames)
        stretch = std::max(stretch, sim::max_stretch(f, setup.rest));
      std::printf(
          "%s: %zu frames, %zu guides x %zu samples, model %s, %.2f s per simulated "
          "second, max stretch %.2g\n",
          opt->output.c_str(), anim.frames.size(), setup.rest.size(),
          setup.rest.empty() ? std::size_t{0} : setup.rest[0].size(),
          sim::choice_name(setup.sim.model), seconds / setup.duration, stretch);
    }
  });
}

}  // namespace wisp::cli
