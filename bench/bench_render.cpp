// wisp-bench render [SCENE] [--runs N]: the main job on the default scene (or SCENE) at 512^2 and
// 1024^2, as a user runs it (`wisp render`, both cores rendering frames): frames per second, the
// first frame's latency (its own time, and from the start of the command to its files), per-stage
// medians from stats.json, the CPU time a frame and the peak memory of the process. The
// simulation is done once beforehand (`wisp simulate`) and read back with --anim, so only
// rendering is measured. Each render runs N times (3 by default) and the median run is reported,
// with every run's frames per second: on a shared machine one run can be 1.3x off the next.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
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

double cpu_seconds(const rusage& u) {
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Runs a command; returns its exit code, the peak resident memory (MB) of the children so far and
// the CPU time (user and system, s) of this command.
int run(const std::string& cmd, double* peak_mb, double* cpu_s = nullptr) {
  rusage before{};
  getrusage(RUSAGE_CHILDREN, &before);
  const int status = std::system((cmd + " > /dev/null 2>&1").c_str());
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  if (peak_mb) *peak_mb = usage.ru_maxrss / 1024.0;
  if (cpu_s) *cpu_s = cpu_seconds(usage) - cpu_seconds(before);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The index of the median of v (the lower one of an even count).
size_t median_index(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  return order[(order.size() - 1) / 2];
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace

int run_render(const std::vector<std::string>& args) {
  const fs::path exe_dir = fs::canonical("/proc/self/exe").parent_path();
  const std::string wisp = (exe_dir / "wisp").string();
  std::string scene = WISP_SOURCE_DIR "/data/scenes/default.json";
  int runs = 3;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] != "--runs") {
      scene = args[i];
      continue;
    }
    const std::string value = i + 1 < args.size() ? args[++i] : "";
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), runs);
    if (error != std::errc() || end != value.data() + value.size() || runs < 1 || runs > 100) {
      std::fprintf(stderr, "wisp-bench render: --runs needs a count of 1 to 100, got '%s'\n",
                   value.c_str());
      return 2;
    }
  }
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
    double peak = 0;
    // First frame alone: what a user waits for before seeing anything; its own time, and from the
    // start of the command (reading the animation, projecting, writing).
    std::vector<double> first_ms, first_after_start_ms;
    for (int r = 0; r < runs; ++r) {
      const fs::path first_dir = dir / ("first" + std::to_string(n));
      run(common + " --frames 0:1 -o " + first_dir.string(), &peak);
      const nlohmann::json first_stats = read_json(first_dir / "stats.json");
      first_ms.push_back(first_stats["frames"][0]["ms"]["frame"]);
      first_after_start_ms.push_back(first_stats["ms"].value("first_frame", 0.0));
    }
    // Every frame; the run with the median frames per second gives the stage medians.
    std::vector<double> fps, cpu_ms_per_frame;
    std::vector<nlohmann::json> stage_medians;
    for (int r = 0; r < runs; ++r) {
      const fs::path out = dir / ("frames" + std::to_string(n));
      double cpu = 0;
      run(common + " --frames 0:" + std::to_string(frames) + " -o " + out.string(), &peak, &cpu);
      const nlohmann::json st = read_json(out / "stats.json");
      fps.push_back(st["frames_per_second"]);
      cpu_ms_per_frame.push_back(1000 * cpu / frames);
      stage_medians.push_back(st["stage_ms_median"]);
    }
    const size_t m = median_index(fps);
    const nlohmann::json entry = {
        {"size", n},
        {"runs", runs},
        {"frames_per_second", fps[m]},
        {"frames_per_second_runs", fps},
        {"cpu_ms_per_frame", cpu_ms_per_frame[m]},
        {"first_frame_ms", first_ms[median_index(first_ms)]},
        {"first_frame_after_start_ms", first_after_start_ms[median_index(first_after_start_ms)]},
        {"peak_memory_mb", peak},
        {"stage_ms_median", stage_medians[m]}};
    std::printf("    %s%s\n", entry.dump().c_str(), i + 1 < 2 ? "," : "");
    std::fflush(stdout);
  }
  std::printf("  ]\n}\n");
  fs::remove_all(dir);
  return 0;
}

}  // namespace wisp::bench
