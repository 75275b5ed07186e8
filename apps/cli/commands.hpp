// The commands of `wisp`. `wisp` itself (wisp.cpp) is a dispatcher that links no stage library:
// it prints the top-level help and runs the executable wisp-<command> from its own folder with the
// same arguments, so that each command loads only the shared libraries it uses (Bullet only where
// hair is simulated or bodies drawn, video support only when a video is written; see "Start-up"
// in docs/performance.md). Each wisp-<command> is command_main.cpp plus the one cmd_<command>.cpp
// that defines add_command, and parses the whole command line as `wisp` would, so help texts and
// errors are the same. A command's callback throws on bad input (a std::exception whose message
// names the file and field); main prints it on one line and exits with code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <cstring>
#include <string>
#include <vector>

namespace wisp::cli {

struct CommandInfo {
  const char* name;
  const char* description;  // one line, in `wisp --help`
};

inline constexpr CommandInfo kCommands[] = {
    {"diffuse", "Render a diffusion-curve drawing (CurveSetXML or SceneXML) to a PNG image"},
    {"simulate", "Simulate a scene's hair and save the animation"},
    {"render", "Simulate a scene (or read a saved animation) and render its frames"},
    {"assemble", "Preview video, contact sheet and merged stats.json of frames rendered in parts"},
    {"farm", "Render an animation on a Slurm cluster (docs/farm.md)"},
};

// The command named `name`, or null.
inline const CommandInfo* find_command(const char* name) {
  for (const CommandInfo& c : kCommands)
    if (std::strcmp(c.name, name) == 0) return &c;
  return nullptr;
}

// The top level of the command line, the same in the dispatcher and in every wisp-<command>.
inline void configure_app(CLI::App& app) {
  app.description("wisp: physically simulated hair rendered as diffusion-curve vector art");
  app.require_subcommand(1);
  app.set_version_flag("--version", "wisp 0.1.0");
}

// Registers the command's subcommand (named and described as in kCommands) on `app`. Defined by
// the one cmd_<name>.cpp linked into wisp-<name>. `command_line`: the whole command line, which
// `wisp farm` records.
void add_command(CLI::App& app, const std::vector<std::string>& command_line);

// The subcommand `name` of kCommands, added to `app`.
inline CLI::App* add_subcommand(CLI::App& app, const char* name) {
  return app.add_subcommand(name, find_command(name)->description);
}

}  // namespace wisp::cli
