// wisp-bench solver: our multigrid against Eigen's ConjugateGradient and SimplicialLDLT on the
// identical discrete problem (same rasterized curves, all 3 channels). The multigrid stops at
// what an 8-bit image can show (SolverOptions::max_error = 0.25/255 of the exact answer), CG at a
// relative residual of 1e-5; both are checked against LDLT's exact answer, and the largest
// differences are printed beside the times, so the comparison shows what each run bought.
// Eigen CG is run only where it finishes in reasonable time; its iteration count grows like the
// image side, so the larger sizes are extrapolated from nothing: they are simply skipped.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/benches.hpp"
#include "diffusion/multigrid.hpp"
#include "diffusion/rasterize.hpp"
#include "diffusion/reference.hpp"

namespace wisp::bench {
namespace {

using diffusion::Color;
using diffusion::DiffusionCurve;

// A drawing that looks like the ones we render: 40 random cubic paths of 4 segments with
// colours on both sides, laid out in the unit square and scaled to the image.
std::vector<DiffusionCurve> bench_drawing(int size, unsigned seed = 12345) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1), step(-0.15, 0.15);
  std::vector<DiffusionCurve> curves;
  for (int k = 0; k < 40; ++k) {
    DiffusionCurve c;
    Eigen::Vector2d p(0.1 + 0.8 * unit(rng), 0.1 + 0.8 * unit(rng));
    for (int i = 0; i < 13; ++i) {
      c.points.push_back(p * size);
      p = (p + Eigen::Vector2d(step(rng), step(rng))).cwiseMax(0.02).cwiseMin(0.98);
    }
    const auto colour = [&] { return Color(float(unit(rng)), float(unit(rng)), float(unit(rng))); };
    c.left = {{0, colour()}, {1, colour()}};
    c.right = {{0, colour()}, {1, colour()}};
    curves.push_back(c);
  }
  return curves;
}

template <class F>
double median_seconds(int repeats, F&& run) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) t.push_back(run());
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int run_solver(const std::vector<std::string>& args) {
  const double tolerance = 1e-5;                                // Eigen CG's relative residual
  const int cg_max = args.empty() ? 1024 : std::stoi(args[0]);  // largest size for Eigen peers
  std::printf(
      "{\n  \"benchmark\": \"solver\",\n  \"tolerance\": %g,\n  \"multigrid_max_error\": "
      "%g,\n  \"sizes\": [\n",
      tolerance, diffusion::kEightBitError);
  // Further arguments pick the sizes (default: 256 to 2048).
  std::vector<int> sizes = {256, 512, 1024, 2048};
  if (args.size() > 1) {
    sizes.clear();
    for (size_t i = 1; i < args.size(); ++i) sizes.push_back(std::stoi(args[i]));
  }
  for (size_t s = 0; s < sizes.size(); ++s) {
    const int n = sizes[s];
    std::fprintf(stderr, "solver bench: %d^2\n", n);
    const diffusion::Problem problem = diffusion::rasterize(bench_drawing(n), n, n);
    diffusion::SolverOptions opt;
    opt.max_error = diffusion::kEightBitError;
    diffusion::SolveStats stats;
    std::vector<float> planes;
    // A solver workspace keeps the operators of its last solve and rebuilds only what changed
    // (a frame after the one before): each timed solve follows another drawing's, so it pays for
    // a new drawing's whole setup. The same drawing solved again is timed apart (`repeat`).
    const diffusion::Problem other = diffusion::rasterize(bench_drawing(n, 54321), n, n);
    const auto seconds = [](const diffusion::Solution& sol) {
      return (sol.stats.setup_ms + sol.stats.solve_ms) / 1000.0;
    };
    // Each answer is written into the last one's storage, as a caller that solves drawing after
    // drawing does (`wisp render` hands its frames' buffers over): a new 12.6 MB answer at 1024^2
    // is pages the allocator returned to the system, 0.7-5 ms of page faults by the host's mood.
    std::vector<float> storage;
    const double mg = median_seconds(5, [&] {
      storage = diffusion::solve_multigrid_into(other, opt, std::move(storage)).planes;
      auto sol = diffusion::solve_multigrid_into(problem, opt, std::move(storage));
      stats = sol.stats;
      storage = std::move(sol.planes);
      return seconds(sol);
    });
    planes = storage;  // the drawing's answer, for the accuracy check below
    diffusion::SolveStats repeat_stats;
    const double repeat = median_seconds(5, [&] {
      auto sol = diffusion::solve_multigrid_into(problem, opt, std::move(storage));
      repeat_stats = sol.stats;
      storage = std::move(sol.planes);
      return seconds(sol);
    });
    std::printf(
        "    {\"size\": %d, \"multigrid_ms\": %.2f, \"multigrid_setup_ms\": %.2f, "
        "\"cycles\": %d, \"final_residual\": %.3g, \"repeat_ms\": %.2f, "
        "\"repeat_setup_ms\": %.2f",
        n, mg * 1000, stats.setup_ms, stats.cycles, stats.final_residual, repeat * 1000,
        repeat_stats.setup_ms);
    // How the stopping rule got there: the relative residual after the FMG start and after each
    // cycle, and the estimated largest error (in 8-bit steps; null before the rule can estimate).
    const auto list = [](const std::vector<double>& v, double scale) {
      std::string out;
      char number[32];
      for (double x : v) {
        std::snprintf(number, sizeof number, "%.3g", scale * x);
        out += (out.empty() ? "" : ", ") + std::string(std::isfinite(x) ? number : "null");
      }
      return "[" + out + "]";
    };
    std::printf(", \"residuals\": %s, \"error_estimates_255\": %s, \"level_ms\": %s",
                list(stats.residual_history, 1).c_str(), list(stats.error_estimates, 255).c_str(),
                list(stats.level_ms, 1).c_str());
    if (n <= cg_max) {
      const auto ldlt =
          diffusion::solve_reference(problem, diffusion::ReferenceMethod::SimplicialLDLT);
      const auto cg = diffusion::solve_reference(
          problem, diffusion::ReferenceMethod::ConjugateGradient, tolerance);
      const auto largest_difference = [&](const std::vector<float>& a) {
        float m = 0;
        for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - ldlt.planes[i]));
        return 255.0 * m;
      };
      std::printf(
          ", \"eigen_ldlt_ms\": %.1f, \"eigen_cg_ms\": %.1f, \"eigen_cg_iterations\": %d, "
          "\"speedup_vs_ldlt\": %.1f, \"speedup_vs_cg\": %.1f, "
          "\"multigrid_error_vs_ldlt_255\": %.3f, \"cg_error_vs_ldlt_255\": %.3f",
          ldlt.seconds * 1000, cg.seconds * 1000, cg.iterations, ldlt.seconds / mg, cg.seconds / mg,
          largest_difference(planes), largest_difference(cg.planes));
    }
    std::printf("}%s\n", s + 1 < sizes.size() ? "," : "");
    std::fflush(stdout);
  }
  std::printf("  ]\n}\n");
  return 0;
}

}  // namespace wisp::bench
