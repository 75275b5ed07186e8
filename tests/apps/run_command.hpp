// Runs a shell command for end-to-end tests and captures its exit code and output.
#pragma once

#include <string>

namespace wisp::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

CommandResult run_command(const std::string& command);

// A fresh empty folder under the system's temporary folder, named after the test.
std::string fresh_folder(const std::string& name);

}  // namespace wisp::test
