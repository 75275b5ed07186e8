// Entry point of the `wisp` command line: one subcommand per main job (see apps/commands.hpp).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "apps/cli/cli_error.hpp"
#include "apps/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"wisp: physically simulated hair rendered as diffusion-curve vector art"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "wisp 0.1.0");
  wisp::cli::add_diffuse_command(app);
  wisp::cli::add_simulate_command(app);
  wisp::cli::add_render_command(app);
  wisp::cli::add_assemble_command(app);
  wisp::cli::add_farm_command(app, std::vector<std::string>(argv, argv + argc));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return wisp::cli::report_parse_error(app, e, "wisp");
  } catch (const std::exception& e) {
    return wisp::cli::report_error("wisp", e.what());
  }
  return 0;
}
