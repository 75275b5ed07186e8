// How the executables report a command-line parse error: one line on stderr naming the program
// and the option, exit code 2 (CLI11's own report adds a second line). --help and --version are
// not errors: CLI11 prints them and the exit code is 0.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>

namespace wisp::cli {

inline int report_parse_error(const CLI::App& app, const CLI::ParseError& e, const char* program) {
  if (e.get_exit_code() == 0) return app.exit(e);
  std::fprintf(stderr, "%s: error: %s\n", program, e.what());
  return 2;
}

}  // namespace wisp::cli
