// run_command and simulated: see run_command.hpp.
#include "run_command.hpp"

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <map>

#include <array>
#include <cstdio>
#include <filesystem>

namespace wisp::test {

CommandResult run_command(const std::string& command) {
  CommandResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

const std::string& simulated(const std::string& scene) {
  static std::map<std::string, std::string> done;
  auto it = done.find(scene);
  if (it != done.end()) return it->second;
  const std::string dir = fresh_folder("anim_" + std::to_string(done.size()));
  const std::string wsim = dir + "/" + std::filesystem::path(scene).stem().string() + ".wsim";
  const CommandResult r =
      run_command(std::string(WISP_BIN_DIR "/wisp simulate ") + scene + " -o " + wsim + " -q");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return done.emplace(scene, wsim).first->second;
}

}  // namespace wisp::test
