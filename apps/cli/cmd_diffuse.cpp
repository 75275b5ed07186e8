// `wisp diffuse IN.xml -o OUT.png`: renders a classic diffusion-curve drawing on its own.
#include <tbb/global_control.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <tuple>

#include "apps/cli/commands.hpp"
#include "apps/render/image_size.hpp"
#include "diffusion/render.hpp"
#include "diffusion/timer.hpp"
#include "io/atomic_file.hpp"
#include "io/drawing_xml.hpp"
#include "io/image_file.hpp"

namespace wisp::cli {
namespace {

struct DiffuseArgs {
  std::string input, output, size, stats, xml;
  double scale = 0;
  double tolerance = 0;  // 0: stop within diffusion::kEightBitError of the exact answer
  int threads = 0;
  bool no_antialias = false;
};

void check_side(int side, const std::string& what) {
  if (side < 1 || side > io::kMaxImageSide)
    throw std::invalid_argument(what + ": image side " + std::to_string(side) +
                                " must be between 1 and " + std::to_string(io::kMaxImageSide));
}

void run_diffuse(const DiffuseArgs& a) {
  const auto t_start = diffusion::Clock::now();
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    size_t(a.threads));

  // Arguments are checked before any work, so that their errors come first and alone.
  int width = 0, height = 0;
  if (!a.size.empty()) std::tie(width, height) = render::parse_size("--size", a.size);
  // Every output path before the work, so that no output is written when one of them is bad.
  io::check_writable(a.output);
  for (const auto& [option, path] : {std::pair{"--stats", a.stats}, std::pair{"--xml", a.xml}})
    if (!path.empty()) try {
        io::check_writable(path);
      } catch (const std::exception& e) {
        throw std::invalid_argument(std::string(option) + ": " + e.what());
      }

  auto t0 = diffusion::Clock::now();
  const io::DrawingFile file = io::read_drawing_xml(a.input);
  const double read_ms = diffusion::ms_since(t0);
  for (const std::string& w : file.warnings) std::fprintf(stderr, "wisp: warning: %s\n", w.c_str());

  if (a.size.empty()) {
    width = file.drawing.width;
    height = file.drawing.height;
  }
  if (a.scale > 0) {
    width = int(std::lround(width * a.scale));
    height = int(std::lround(height * a.scale));
  }
  check_side(width, "--scale");
  check_side(height, "--scale");

  diffusion::SolverOptions solver;
  if (a.tolerance > 0)
    solver.tolerance = a.tolerance;
  else
    solver.max_error = diffusion::kEightBitError;
  diffusion::RenderStats st;
  const diffusion::Image image =
      diffusion::render_drawing(file.drawing, width, height, solver, &st, !a.no_antialias);
  if (!st.solver.converged) {
    if (a.tolerance > 0)
      std::fprintf(stderr,
                   "wisp: warning: the solver stopped at relative residual %.2g (asked %.2g)\n",
                   st.solver.final_residual, a.tolerance);
    else
      std::fprintf(stderr,
                   "wisp: warning: the solver stopped before its error estimate reached 0.25/255 "
                   "(relative residual %.2g)\n",
                   st.solver.final_residual);
  }

  t0 = diffusion::Clock::now();
  io::write_png(a.output, image);
  if (!a.xml.empty()) io::write_drawing_xml(file.drawing, a.xml);
  const double write_ms = diffusion::ms_since(t0);

  if (!a.stats.empty()) {
    nlohmann::json j;
    j["input"] = a.input;
    j["output"] = a.output;
    j["width"] = width;
    j["height"] = height;
    j["curves"] = file.drawing.curves.size();
    j["warnings"] = file.warnings;
    j["times_ms"] = {{"read", read_ms},
                     {"rasterize", st.rasterize_ms},
                     {"solve", st.solve_ms},
                     {"antialias", st.antialias_ms},
                     {"blur", st.blur_ms},
                     {"write", write_ms},
                     {"total", diffusion::ms_since(t_start)}};
    j["solver"] = {{"levels", st.solver.levels},
                   {"cycles", st.solver.cycles},
                   {"setup_ms", st.solver.setup_ms},
                   {"level_ms", st.solver.level_ms},
                   {"initial_residual", st.solver.initial_residual},
                   {"final_residual", st.solver.final_residual},
                   {"residual_history", st.solver.residual_history},
                   {"converged", st.solver.converged},
                   {"floating_pixels", st.solver.floating_pixels}};
    j["blurred"] = st.blurred;
    j["antialiased_pixels"] = st.antialiased_pixels;
    io::write_text_atomically(a.stats, j.dump(2) + "\n");
  }
}

}  // namespace

void add_command(CLI::App& app, const std::vector<std::string>&) {
  auto args = std::make_shared<DiffuseArgs>();
  CLI::App* cmd = add_subcommand(app, "diffuse");
  cmd->add_option("input", args->input, "Drawing (.xml)")->required();
  cmd->add_option("-o,--output", args->output, "Output image (.png)")->required();
  auto* size = cmd->add_option("--size", args->size, "Output size WxH (default: the drawing's)");
  cmd->add_option("--scale", args->scale, "Scale the drawing's own size by S")
      ->excludes(size)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--stats", args->stats, "Write timings and solver statistics as JSON");
  cmd->add_option("--xml", args->xml, "Also write the drawing as SceneXML (a format conversion)");
  cmd->add_option("--tolerance", args->tolerance,
                  "Stop the solve at this relative residual instead of within 0.25/255 of "
                  "the exact discrete answer (the default)")
      ->check(CLI::Range(1e-12, 1e-1));
  cmd->add_flag("--no-antialias", args->no_antialias,
                "Keep each pixel's solved colour along sharp curves (today's output of other "
                "diffusion-curve renderers, for comparison)");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 256));
  cmd->callback([args] { run_diffuse(*args); });
}

}  // namespace wisp::cli
