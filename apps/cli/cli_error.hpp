// How the executables report a command-line parse error: one line on stderr naming the program
// and the option, exit code 2 (CLI11's own report adds a second line). --help and --version are
// not errors: CLI11 prints them and the exit code is 0.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

namespace wisp::cli {

// Prints "<program>: error: <what>" as one line: control characters that came from the input (a
// JSON key with a newline in it) are shown as spaces.
inline int report_error(const char* program, std::string what) {
  for (char& c : what)
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  std::fprintf(stderr, "%s: error: %s\n", program, what.c_str());
  return 2;
}

inline int report_parse_error(const CLI::App& app, const CLI::ParseError& e, const char* program) {
  if (e.get_exit_code() == 0) return app.exit(e);
  std::fprintf(stderr, "%s: error: %s\n", program, e.what());
  return 2;
}

}  // namespace wisp::cli
