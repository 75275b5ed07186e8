// The subcommands of the `wisp` executable. Each lives in its own apps/cmd_<name>.cpp and
// registers itself on the CLI11 app; wisp.cpp only lists them. A command's callback throws on bad
// input (a std::exception whose message names the file and field); main prints it on one line and
// exits with code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace wisp::cli {

void add_diffuse_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_assemble_command(CLI::App& app);
// `command`: the whole command line, recorded in OUTDIR/farm.json.
void add_farm_command(CLI::App& app, const std::vector<std::string>& command);

}  // namespace wisp::cli
