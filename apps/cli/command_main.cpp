// main() of every wisp-<command> executable (see commands.hpp): the top level of `wisp` with the
// one command this executable holds, parsed from the command line `wisp` was given.
#include <exception>
#include <string>
#include <vector>

#include "apps/cli/cli_error.hpp"
#include "apps/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app;
  wisp::cli::configure_app(app);
  wisp::cli::add_command(app, std::vector<std::string>(argv, argv + argc));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return wisp::cli::report_parse_error(app, e, "wisp");
  } catch (const std::exception& e) {
    return wisp::cli::report_error("wisp", e.what());
  }
  return 0;
}
