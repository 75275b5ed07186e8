// Runs a shell command for end-to-end tests and captures its exit code and output.
#pragma once

#include <string>

#include "tests/test_folder.hpp"  // fresh_folder, for the tests that run commands

namespace wisp::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

CommandResult run_command(const std::string& command);

// `wisp simulate scene -o <file>`, run once per test process and scene (ctest runs test cases
// in parallel processes, so each has its own copy); returns the saved animation's path.
const std::string& simulated(const std::string& scene);

}  // namespace wisp::test
