// wisp-bench NAME [args...]: runs one benchmark (or `all`) and prints JSON. Benchmarks are never
// part of the test suite and never fail on a time; they report numbers and ratios to peers.
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bench/benches.hpp"

int main(int argc, char** argv) {
  using Bench = std::function<int(const std::vector<std::string>&)>;
  const std::map<std::string, Bench> benches = {
      {"solver", wisp::bench::run_solver},   {"arrangement", wisp::bench::run_arrangement},
      {"sim", wisp::bench::run_sim},         {"render", wisp::bench::run_render},
      {"quality", wisp::bench::run_quality}, {"diffuse", wisp::bench::run_diffuse},
      {"groom", wisp::bench::run_groom},     {"frame-table", wisp::bench::run_frame_table},
      {"fronts", wisp::bench::run_fronts},
  };
  if (argc < 2) {
    std::fprintf(stderr, "usage: wisp-bench NAME [args...]   NAME: all");
    for (const auto& [name, _] : benches) std::fprintf(stderr, " | %s", name.c_str());
    std::fprintf(stderr, "\n");
    return 2;
  }
  const std::string name = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  if (name == "all") {
    int rc = 0;
    for (const auto& [bench, run] : benches)
      if (bench != "frame-table") rc |= run(args);  // it repeats the others
    return rc;
  }
  const auto it = benches.find(name);
  if (it == benches.end()) {
    std::fprintf(stderr, "wisp-bench: unknown benchmark '%s'\n", name.c_str());
    return 2;
  }
  return it->second(args);
}
