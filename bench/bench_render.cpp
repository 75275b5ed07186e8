// wisp-bench render: the main job on the default scene at 512^2 and 1024^2, as a user runs it
// (`wisp render`, both cores rendering frames): frames per second, the first frame's latency (its
// own time, and from the start of the command to its files),
// per-stage medians from stats.json and the peak memory of the process. The simulation is done
// once beforehand (`wisp simulate`) and read back with --anim, so only rendering is measured.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/benches.hpp"

namespace wisp::bench {
namespace {

namespace fs = std::filesystem;

// Runs a command; returns its exit code and the peak resident memory (MB) of the children so far.
int run(const std::string& cmd, double* peak_mb) {
  const int status = std::system((cmd + " > /dev/null 2>&1").c_str());
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  if (peak_mb) *peak_mb = usage.ru_maxrss / 1024.0;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace

int run_render(const std::vector<std::string>& args) {
  const fs::path exe_dir = fs::canonical("/proc/self/exe").parent_path();
  const std::string wisp = (exe_dir / "wisp").string();
  const std::string scene =
      args.empty() ? std::string(WISP_SOURCE_DIR "/data/scenes/default.json") : args[0];
  const int frames = 24;
  const fs::path dir =
      fs::temp_directory_path() / ("wisp_bench_render_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string anim = (dir / "anim.wsim").string();
  if (run(wisp + " simulate " + scene + " -o " + anim + " -q", nullptr) != 0) {
    std::fprintf(stderr, "wisp-bench render: simulation of %s failed\n", scene.c_str());
    return 1;
  }
  std::printf(
      "{\n  \"benchmark\": \"render\",\n  \"scene\": \"%s\",\n  \"frames\": %d,\n  \"sizes\": [\n",
      scene.c_str(), frames);
  const int sizes[] = {512, 1024};
  for (size_t i = 0; i < 2; ++i) {
    const int n = sizes[i];
    std::fprintf(stderr, "render bench: %d^2\n", n);
    const std::string common = wisp + " render " + scene + " --anim " + anim + " --size " +
                               std::to_string(n) + "x" + std::to_string(n) + " -q --force";
    // First frame alone: what a user waits for before seeing anything.
    const fs::path first_dir = dir / ("first" + std::to_string(n));
    double peak = 0;
    run(common + " --frames 0:1 -o " + first_dir.string(), &peak);
    const nlohmann::json first_stats = read_json(first_dir / "stats.json");
    const double first_ms = first_stats["frames"][0]["ms"]["frame"];
    // The same frame from the start of the command (reading the animation, projecting, writing).
    const double first_after_start_ms = first_stats["ms"].value("first_frame", 0.0);
    const fs::path out = dir / ("frames" + std::to_string(n));
    run(common + " --frames 0:" + std::to_string(frames) + " -o " + out.string(), &peak);
    const nlohmann::json st = read_json(out / "stats.json");
    std::printf(
        "    {\"size\": %d, \"frames_per_second\": %.2f, \"first_frame_ms\": %.1f, "
        "\"first_frame_after_start_ms\": %.1f, \"peak_memory_mb\": %.0f, "
        "\"stage_ms_median\": %s}%s\n",
        n, st["frames_per_second"].get<double>(), first_ms, first_after_start_ms, peak,
        st["stage_ms_median"].dump().c_str(), i + 1 < 2 ? "," : "");
    std::fflush(stdout);
  }
  std::printf("  ]\n}\n");
  fs::remove_all(dir);
  return 0;
}

}  // namespace wisp::bench
