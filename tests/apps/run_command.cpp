// run_command and simulated: see run_command.hpp.
#include "run_command.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <vector>

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

namespace {

// What the simulation of `scene` depends on, as text: the scene, every file under data/ (name,
// size, time) and the simulator.
std::string simulation_inputs(const std::string& scene) {
  namespace fs = std::filesystem;
  const auto stamp = [](const fs::path& f) {
    return f.string() + " " + std::to_string(fs::file_size(f)) + " " +
           std::to_string(fs::last_write_time(f).time_since_epoch().count()) + "\n";
  };
  std::ifstream in(scene, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(WISP_SOURCE_DIR "/data"))
    if (e.is_regular_file()) files.push_back(stamp(e.path()));
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) text += f;
  return text + stamp(fs::canonical(WISP_BIN_DIR "/wisp-simulate"));
}

}  // namespace

const std::string& simulated(const std::string& scene) {
  static std::map<std::string, std::string> done;
  auto it = done.find(scene);
  if (it != done.end()) return it->second;
  namespace fs = std::filesystem;
  const fs::path cache = fs::path(WISP_BIN_DIR).parent_path() / "test-cache";
  fs::create_directories(cache);
  char name[17];
  std::snprintf(name, sizeof name, "%016zx", std::hash<std::string>{}(simulation_inputs(scene)));
  const std::string prefix = fs::path(scene).stem().string() + "-";
  const std::string wsim = (cache / (prefix + name + ".wsim")).string();
  if (!fs::exists(wsim)) {
    // Simulated beside the cache file under this process's own name, then renamed into place.
    const std::string partial = wsim + ".partial-" + std::to_string(::getpid());
    const CommandResult r =
        run_command(std::string(WISP_BIN_DIR "/wisp simulate ") + scene + " -o " + partial + " -q");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    fs::rename(partial, wsim);
    // The scene's animations of earlier builds (8.7 MB each for the default scene) go.
    for (const auto& e : fs::directory_iterator(cache)) {
      const std::string file = e.path().filename().string();
      if (file.rfind(prefix, 0) == 0 && e.path().extension() == ".wsim" && e.path() != wsim &&
          file.size() == fs::path(wsim).filename().string().size()) {
        std::error_code ignored;  // another process may have removed it first
        fs::remove(e.path(), ignored);
      }
    }
  }
  return done.emplace(scene, wsim).first->second;
}

}  // namespace wisp::test
