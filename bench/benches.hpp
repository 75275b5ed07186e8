// The benchmarks of wisp-bench. Each lives in bench/bench_<name>.cpp, prints one JSON document on
// stdout (progress on stderr) and compares against its named peers in the same run.
#pragma once

#include <string>
#include <vector>

namespace wisp::bench {

// Each returns the process exit code. `args` are the arguments after the benchmark's name.
int run_solver(const std::vector<std::string>& args);
int run_arrangement(const std::vector<std::string>& args);
int run_sim(const std::vector<std::string>& args);
int run_render(const std::vector<std::string>& args);
int run_quality(const std::vector<std::string>& args);
int run_fronts(const std::vector<std::string>& args);
int run_diffuse(const std::vector<std::string>& args);
int run_groom(const std::vector<std::string>& args);
// Every row of docs/performance.md's frame table, from the others; not part of `all`.
int run_frame_table(const std::vector<std::string>& args);

}  // namespace wisp::bench
