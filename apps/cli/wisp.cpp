// Entry point of the `wisp` command line: a dispatcher (see commands.hpp). `wisp <command> ...`
// replaces itself (execv) with wisp-<command> from its own folder, passing every argument as
// given; anything else (no command, --help, --version, a word that is no command) is answered
// here, by the same top-level parser the commands use. Links no stage library: its start-up is
// that of a plain C++ program.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "apps/cli/cli_error.hpp"
#include "apps/cli/commands.hpp"
#include "util/module.hpp"

int main(int argc, char** argv) {
  using namespace wisp::cli;
  // The top level has flags only (-h, --version), so the first argument that is not an option
  // is the command, as CLI11 would read it.
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-') continue;
    const CommandInfo* command = find_command(argv[i]);
    if (!command) break;
    const std::string exe =
        (wisp::util::executable_dir() / ("wisp-" + std::string(command->name))).string();
    execv(exe.c_str(), argv);
    return report_error("wisp", "cannot run the " + std::string(command->name) + " command (" +
                                    exe + ": " + std::strerror(errno) +
                                    "); build or install wisp whole");
  }
  CLI::App app;
  configure_app(app);
  for (const CommandInfo& c : kCommands) app.add_subcommand(c.name, c.description);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return report_parse_error(app, e, "wisp");
  }
  return 0;
}
