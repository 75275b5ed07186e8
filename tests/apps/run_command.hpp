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

// The saved animation of `wisp simulate scene`, made once for every test process of this build:
// ctest runs each test case in a process of its own, and the default scene alone simulates in
// 3-4 s, which dozens of cases need. The file is kept in the build folder (test-cache/), named by
// a hash of the scene's text, the files under data/ (their paths, sizes and times) and the
// simulator executable's size and time, so an edited scene, asset or simulator makes a new one;
// it is written to a temporary name and renamed, so parallel cases never read half a file, and
// replaces the scene's animations of earlier builds.
const std::string& simulated(const std::string& scene);

}  // namespace wisp::test
