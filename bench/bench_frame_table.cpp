// wisp-bench frame-table: every row of the frame-rate table of issue 13 (docs/performance.md) in
// one run, each next to its target: the render of the default scene (frames per second at 512^2
// and 1024^2, the median of three runs with their spread and the CPU time a frame; first frame,
// peak memory, per-stage medians), the solver at 512^2 and 1024^2
// against Eigen's LDLT and CG, `wisp diffuse` of a 1024^2 drawing as a whole process, the
// arrangement of 1000 plain wisps and the start-up of `wisp diffuse --help`. The rows come from
// the other benchmarks (run as child processes of this executable, so each starts cold) and from
// timing the wisp executable itself; the machine should be quiet, since every row is a wall time.
// Before and after the rows it reads the host's speed by workloads that no commit changes (core,
// memory, fresh pages: "host" in the JSON), so tables of different days can be told apart.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "bench/benches.hpp"
#include "diffusion/timer.hpp"

namespace wisp::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Runs a command and returns its standard output ("" when it fails).
std::string output_of(const std::string& cmd) {
  std::string out;
  FILE* pipe = popen((cmd + " 2>/dev/null").c_str(), "r");
  if (!pipe) return out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  return pclose(pipe) == 0 ? out : std::string();
}

json parse_or_null(const std::string& text) {
  return text.empty() ? json() : json::parse(text, nullptr, false);
}

// Wall milliseconds and peak resident MB of one run of a command (output discarded): forked, so
// that the peak is this child's alone.
std::pair<double, double> timed_run(const std::vector<std::string>& argv) {
  const auto t0 = diffusion::Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(127);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  return {diffusion::ms_since(t0), usage.ru_maxrss / 1024.0};
}

template <class F>
std::pair<double, double> median_run(int repeats, F&& run) {
  std::vector<double> ms, mb;
  for (int i = 0; i < repeats; ++i) {
    const auto [t, m] = run();
    ms.push_back(t);
    mb.push_back(m);
  }
  std::sort(ms.begin(), ms.end());
  std::sort(mb.begin(), mb.end());
  return {ms[ms.size() / 2], mb[mb.size() / 2]};
}

// Shared libraries the dynamic loader maps while running `command`, as it reports them
// (LD_DEBUG=files): `wisp` and the wisp-<command> it runs together, each library once.
int shared_libraries(const std::string& command) {
  std::istringstream lines(output_of("{ LD_DEBUG=files " + command + " 2>&1 >/dev/null; }"));
  std::set<std::string> files;
  for (std::string line; std::getline(lines, line);) {
    const auto at = line.find("file=");
    if (at != std::string::npos) files.insert(line.substr(at + 5, line.find(' ', at) - at - 5));
  }
  return int(files.size());
}

struct Row {
  std::string work, measured, target;
  bool meets = false;
};

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

const json* find_size(const json& doc, int size) {
  if (!doc.is_object() || !doc.contains("sizes")) return nullptr;
  for (const json& s : doc["sizes"])
    if (s.value("size", 0) == size) return &s;
  return nullptr;
}

// How fast this host runs today, by three fixed workloads that no commit changes: the rows' times
// are wall times on shared virtual machines whose speed moves by 1.6x from one day to the next
// (docs/performance.md), and these say which kind of day a table was measured on.
struct HostSpeed {
  double chain_ns = 0;         // one dependent double multiply-add (core clock and steal)
  double triad_gb_s = 0;       // c = a + 0.5 b over three 64 MB arrays, one thread (memory)
  double fresh_ms_per_mb = 0;  // first write of new pages (the kernel's zeroing, host faults)
};

HostSpeed measure_host() {
  HostSpeed h;
  volatile double seed = 1.0;  // not known to the compiler: the chain is computed
  double x = seed;
  constexpr long kSteps = 40'000'000;
  auto t0 = diffusion::Clock::now();
  for (long i = 0; i < kSteps; ++i) x = x * 0.999999 + 1e-7;
  h.chain_ns = diffusion::ms_since(t0) * 1e6 / kSteps;
  seed = x;
  constexpr size_t kFloats = size_t(64) << 18;  // 64 MB of floats per array
  constexpr double kMb = 3 * 64.0;
  t0 = diffusion::Clock::now();
  std::vector<float> a(kFloats, 1.0f), b(kFloats, 2.0f), c(kFloats, 0.0f);
  h.fresh_ms_per_mb = diffusion::ms_since(t0) / kMb;
  double best = 1e300;
  for (int r = 0; r < 5; ++r) {
    t0 = diffusion::Clock::now();
    for (size_t i = 0; i < kFloats; ++i) c[i] = a[i] + 0.5f * b[i];
    best = std::min(best, diffusion::ms_since(t0));
    a[r] = c[kFloats - 1 - r];  // each pass's result is used
  }
  h.triad_gb_s = kMb * 1.048576 / best;  // MB of 2^20 bytes per ms -> GB/s
  return h;
}

json host_json(const HostSpeed& h) {
  return {{"dependent_multiply_add_ns", h.chain_ns},
          {"triad_one_thread_gb_s", h.triad_gb_s},
          {"fresh_pages_ms_per_mb", h.fresh_ms_per_mb}};
}

// " (median of 3 runs: 5.1 - 6.0; CPU 350 ms a frame)" for a size of `wisp-bench render`: the
// spread says how far to trust the median on a shared machine, the CPU time is the work done.
std::string runs_of(const json& size) {
  const json runs = size.value("frames_per_second_runs", json::array());
  if (runs.size() < 2) return "";
  const auto [lo, hi] = std::minmax_element(runs.begin(), runs.end());
  return fmt(" (median of %.0f runs: %.2f - %.2f; ", double(runs.size()), lo->get<double>(),
             hi->get<double>()) +
         fmt("CPU %.0f ms a frame)", size.value("cpu_ms_per_frame", 0.0));
}

}  // namespace

int run_frame_table(const std::vector<std::string>&) {
  const fs::path exe_dir = fs::canonical("/proc/self/exe").parent_path();
  const std::string self = (exe_dir / "wisp-bench").string(), wisp = (exe_dir / "wisp").string();
  std::vector<Row> rows;
  std::fprintf(stderr, "frame-table: host\n");
  const HostSpeed host_before = measure_host();

  std::fprintf(stderr, "frame-table: render\n");
  const json render = parse_or_null(output_of(self + " render"));
  const json* r1024 = find_size(render, 1024);
  const json* r512 = find_size(render, 512);
  if (r1024) {
    const json& s = *r1024;
    const double fps = s["frames_per_second"], first = s["first_frame_ms"],
                 after_start = s.value("first_frame_after_start_ms", 0.0), mb = s["peak_memory_mb"];
    rows.push_back(
        {"wisp-bench render, default scene, 24 frames, 1024^2",
         fmt("%.2f frames/s", fps) + runs_of(s) +
             fmt(", first frame %.0f ms (written %.0f ms after start), ", first, after_start) +
             fmt("peak %.0f MB", mb),
         ">= 6 frames/s, first frame <= 300 ms, <= 300 MB", fps >= 6 && first <= 300 && mb <= 300});
    const json& m = s["stage_ms_median"];
    const double arr = m.value("arrangement", 0.0), sweep = m.value("arrangement_sweep", 0.0),
                 solve = m.value("solve", 0.0), write = m.value("write", 0.0),
                 write_cpu = m.value("write_cpu", 0.0), write_wait = m.value("write_wait", 0.0),
                 wisps = m.value("wisps", 0.0);
    rows.push_back({"per-frame medians at 1024^2",
                    fmt("arrangement %.0f ms (sweep %.0f), solve %.0f, ", arr, sweep, solve) +
                        fmt("write %.0f (CPU %.0f, on the writer thread; frames waited %.1f), ",
                            write, write_cpu, write_wait) +
                        fmt("wisps %.0f", wisps),
                    "arrangement <= 100, solve <= 60, write <= 25, wisps <= 15",
                    arr <= 100 && solve <= 60 && write <= 25 && wisps <= 15});
  }
  if (r512) {
    const double fps = (*r512)["frames_per_second"];
    rows.push_back(
        {"same at 512^2", fmt("%.2f frames/s", fps) + runs_of(*r512), ">= 15 frames/s", fps >= 15});
  }

  std::fprintf(stderr, "frame-table: solver\n");
  const json solver = parse_or_null(output_of(self + " solver 1024"));
  const json* s1024 = find_size(solver, 1024);
  const json* s512 = find_size(solver, 512);
  if (s1024 && s512) {
    const double ms = (*s1024)["multigrid_ms"], setup = (*s1024)["multigrid_setup_ms"],
                 ldlt = (*s1024).value("speedup_vs_ldlt", 0.0),
                 cg = (*s1024).value("speedup_vs_cg", 0.0);
    rows.push_back({"wisp-bench solver 1024^2, 3 channels, within 0.25/255 (CG: 1e-5)",
                    fmt("%.0f ms, of it setup %.0f ms; %.1fx LDLT, %.1fx CG", ms, setup, ldlt, cg),
                    "<= 40 ms: >= 80x LDLT and >= 400x CG in the same run",
                    ms <= 40 && ldlt >= 80 && cg >= 400});
    const double ms512 = (*s512)["multigrid_ms"], setup512 = (*s512)["multigrid_setup_ms"];
    rows.push_back({"same at 512^2",
                    fmt("%.0f ms (setup %.0f ms): 1024^2 costs %.1fx", ms512, setup512, ms / ms512),
                    "<= 12 ms, and 1024^2 at most 4.5x of 512^2",
                    ms512 <= 12 && ms / ms512 <= 4.5});
  }

  std::fprintf(stderr, "frame-table: diffuse\n");
  const fs::path dir = fs::temp_directory_path() / ("wisp_bench_table_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string drawing = WISP_SOURCE_DIR "/data/drawings/wisps.xml";
  const std::string png = (dir / "d.png").string(), stats = (dir / "d.json").string();
  // Each run's own rasterize + setup, read after it: the median of those beside the median wall
  // (the last run's alone could be the slowest, and larger than the median wall).
  std::vector<double> setups;
  const auto diffuse = median_run(3, [&] {
    const auto run =
        timed_run({wisp, "diffuse", drawing, "-o", png, "--size", "1024x1024", "--stats", stats});
    std::ifstream stats_in(stats);
    const json d = json::parse(stats_in, nullptr, false);
    setups.push_back(d.is_object() ? d["solver"].value("setup_ms", 0.0) +
                                         d["times_ms"].value("rasterize", 0.0)
                                   : 0.0);
    return run;
  });
  std::sort(setups.begin(), setups.end());
  rows.push_back({"wisp diffuse of a 1024^2 drawing, whole process",
                  fmt("%.0f ms, rasterize + solver setup %.0f ms (medians)", diffuse.first,
                      setups[setups.size() / 2]),
                  "<= 100 ms", diffuse.first <= 100});

  std::fprintf(stderr, "frame-table: arrangement\n");
  const json arrangement =
      parse_or_null(output_of(self + " arrangement --exact-timeout 0 --repeats 3"));
  if (arrangement.is_object())
    for (const json& scene : arrangement["scenes"])
      for (const json& s : scene["sizes"])
        if (scene["scene"] == "plain" && s["wisps"] == 1000) {
          const double ms = s["arrangement_ms"];
          rows.push_back({"wisp-bench arrangement, 1000 plain wisps", fmt("%.0f ms", ms),
                          "<= 200 ms", ms <= 200});
        }

  std::fprintf(stderr, "frame-table: start-up\n");
  const auto help = median_run(5, [&] { return timed_run({wisp, "diffuse", "--help"}); });
  rows.push_back({"start-up: wisp diffuse --help",
                  fmt("%.3f s and %.0f MB, %.0f shared libraries", help.first / 1000, help.second,
                      shared_libraries(wisp + " diffuse --help")),
                  "<= 30 ms; a command loads what it uses", help.first <= 30});
  fs::remove_all(dir);

  // The host again: a table whose two readings differ was measured while the host changed.
  const HostSpeed host_after = measure_host();
  json out = {{"benchmark", "frame-table"},
              {"host", {{"before", host_json(host_before)}, {"after", host_json(host_after)}}},
              {"rows", json::array()}};
  for (const Row& r : rows)
    out["rows"].push_back(
        {{"work", r.work}, {"measured", r.measured}, {"target", r.target}, {"meets", r.meets}});
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}

}  // namespace wisp::bench
