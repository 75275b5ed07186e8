// wisp-bench arrangement: wisp construction and the exact segment arrangement (sweep, then
// coverage, depth order, visibility, mask and ink lines) for 50..1000 random wisps, against the
// exact Bezier traits on the same outlines where those finish. Two scenes: "plain" wisps like
// the prior-work micro-benchmark (60-140 px long, gently bent, 6-12 px wide) and "mixed" hair
// (a third each straight, wavy and curly, as in the tests). The exact run happens in a forked
// child with a time limit, because the Bezier traits can take minutes or crash. Times are wall
// times and, for comparisons on a loaded machine, the arrangement's CPU time (sweep_cpu_ms,
// arrangement_cpu_ms: the calling thread's). The peer in the same run: CGAL's sweep over the
// same segments (cgal_sweep_ms, and its ratio to ours).
//
// Arguments: [--exact-timeout SECONDS] (default 60; 0 skips the exact traits) [--repeats N]
// [--scene plain|mixed] (default both) [--wisps N] (one size instead of 50..1000).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "bench/benches.hpp"
#include "diffusion/timer.hpp"
#include "vector/arrangement.hpp"
#include "vector/wisp.hpp"

namespace wisp::bench {
namespace {

using Eigen::Vector2d;

sim::ProjectedStrand sampled(int id, int samples, const std::function<Eigen::Vector3d(double)>& q) {
  sim::ProjectedStrand s;
  s.id = id;
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector3d p = q(double(i) / (samples - 1));
    s.pixel.emplace_back(p.x(), p.y());
    s.depth.push_back(p.z());
  }
  return s;
}

sim::ProjectedFrame bench_frame(int count, bool mixed, std::uint32_t seed) {
  std::mt19937 rng(seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  sim::ProjectedFrame f;
  f.width = f.height = 512;
  f.focal_px = 800;
  for (int i = 0; i < count; ++i) {
    const Vector2d root(uni(0, 512), uni(0, 512));
    const double angle = uni(0, 2 * M_PI);
    const Vector2d dir(std::cos(angle), std::sin(angle)), side(-dir.y(), dir.x());
    const double z0 = uni(2, 4), dz = uni(-0.3, 0.3), bend = uni(-0.3, 0.3);
    const int kind = mixed ? i % 3 : 0;
    const double length = mixed ? uni(60, 180) : uni(60, 140);
    if (kind == 0) {
      f.strands.push_back(sampled(i, mixed ? 10 : 6, [=](double u) {
        const Vector2d p = root + dir * length * u + side * bend * length * u * u;
        return Eigen::Vector3d(p.x(), p.y(), z0 + dz * u);
      }));
    } else if (kind == 1) {
      const double a = uni(3, 10), waves = length / uni(30, 60), ph = uni(0, 2 * M_PI);
      f.strands.push_back(sampled(i, 8 + int(6 * waves), [=](double u) {
        const Vector2d p = root + dir * length * u +
                           side * (a * std::sin(2 * M_PI * waves * u + ph) + bend * length * u * u);
        return Eigen::Vector3d(p.x(), p.y(), z0 + dz * u);
      }));
    } else {
      const double r = uni(5, 12), turns = length / uni(25, 45), ph = uni(0, 2 * M_PI);
      const double tilt = uni(0.3, 0.9);
      f.strands.push_back(sampled(i, 8 + int(8 * turns), [=](double u) {
        const double a = 2 * M_PI * turns * u + ph;
        const Vector2d p =
            root + dir * (length * u + tilt * r * std::cos(a)) + side * r * std::sin(a);
        return Eigen::Vector3d(p.x(), p.y(), z0 + dz * u + 0.01 * r * std::cos(a));
      }));
    }
  }
  return f;
}

// Runs the exact Bezier arrangement in a child process; "null" on timeout or failure.
std::string exact_in_child(const std::vector<vector::Wisp>& wisps, double timeout_s) {
  int fd[2];
  if (pipe(fd) != 0) return "null";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    char buf[256];
    try {
      const auto t = vector::exact_bezier_topology(wisps);
      std::snprintf(buf, sizeof buf,
                    "{\"ms\": %.1f, \"vertices\": %ld, \"edges\": %ld, \"faces\": %ld}", t.ms,
                    t.vertices, t.edges, t.faces);
    } catch (const std::exception& e) {
      std::snprintf(buf, sizeof buf, "{\"error\": \"CGAL failed\"}");
    }
    if (write(fd[1], buf, std::strlen(buf)) < 0) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  const auto t0 = diffusion::Clock::now();
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (diffusion::ms_since(t0) > timeout_s * 1000) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      close(fd[0]);
      return "\"timeout\"";
    }
    usleep(20000);
  }
  char buf[256] = {0};
  const ssize_t n = read(fd[0], buf, sizeof buf - 1);
  close(fd[0]);
  if (!WIFEXITED(status) || n <= 0) return "\"crashed\"";
  return buf;
}

}  // namespace

int run_arrangement(const std::vector<std::string>& args) {
  double exact_timeout = 60;
  int repeats = 5;
  std::vector<int> sizes = {50, 100, 200, 400, 1000};
  std::vector<int> scenes = {0, 1};  // plain, mixed
  for (size_t i = 0; i + 1 < args.size(); i += 2) {
    if (args[i] == "--exact-timeout") exact_timeout = std::stod(args[i + 1]);
    if (args[i] == "--repeats") repeats = std::max(1, std::stoi(args[i + 1]));
    if (args[i] == "--wisps") sizes = {std::max(1, std::stoi(args[i + 1]))};
    if (args[i] == "--scene") scenes = {args[i + 1] == "mixed" ? 1 : 0};
  }
  vector::WispStyle style;
  style.width = 0.03;
  vector::ArrangementOptions options;
  options.view = vector::image_rect(512, 512);

  std::printf("{\n  \"benchmark\": \"arrangement\",\n  \"image\": [512, 512],\n");
  std::printf("  \"flatten_tolerance_px\": %g,\n  \"fit_tolerance_px\": %g,\n  \"repeats\": %d,\n",
              style.flatten_tolerance_px, style.fit_tolerance_px, repeats);
  std::printf("  \"scenes\": [\n");
  for (size_t k = 0; k < scenes.size(); ++k) {
    const int mixed = scenes[k];
    std::printf("    {\"scene\": \"%s\", \"sizes\": [\n", mixed ? "mixed" : "plain");
    bool exact_gave_up = exact_timeout <= 0;
    for (size_t s = 0; s < sizes.size(); ++s) {
      const int n = sizes[s];
      std::fprintf(stderr, "arrangement bench: %s, %d wisps\n", mixed ? "mixed" : "plain", n);
      const sim::ProjectedFrame frame = bench_frame(n, mixed, 1000 + n);
      std::vector<double> build, cull, sweep, resolve, total, sweep_cpu, total_cpu;
      std::vector<vector::Wisp> wisps;
      vector::WispArrangement arr;
      for (int r = 0; r < repeats; ++r) {
        const auto t0 = diffusion::Clock::now();
        wisps = vector::build_wisps(frame, style);
        build.push_back(diffusion::ms_since(t0));
        const auto t1 = diffusion::Clock::now();
        arr = vector::build_arrangement(wisps, options);
        total.push_back(diffusion::ms_since(t1));
        cull.push_back(arr.stats.cull_ms);
        sweep.push_back(arr.stats.sweep_ms);
        resolve.push_back(arr.stats.resolve_ms);
        sweep_cpu.push_back(arr.stats.sweep_cpu_ms);
        total_cpu.push_back(arr.stats.sweep_cpu_ms + arr.stats.resolve_cpu_ms);
      }
      auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
      };
      long cubics = 0;
      for (const auto& w : wisps) cubics += w.outline.piece_count();
      std::string exact = "null";
      if (!exact_gave_up) {
        vector::ArrangementOptions unclipped;
        unclipped.clip_to_view = false;
        const auto plain = vector::build_arrangement(wisps, unclipped);
        exact = exact_in_child(wisps, exact_timeout);
        if (exact.front() == '{')
          exact.insert(exact.size() - 1,
                       ", \"segment_faces_unclipped\": " + std::to_string(plain.stats.faces));
        else
          exact_gave_up = true;  // larger sizes only take longer
      }
      // CGAL's sweep on the same segments, the peer of ours (sweep_ms), in the same run.
      std::vector<double> cgal_sweep;
      vector::ArrangementOptions cgal = options;
      cgal.arrange = vector::arrange_segments_cgal;
      for (int r = 0; r < repeats; ++r)
        cgal_sweep.push_back(vector::build_arrangement(wisps, cgal).stats.sweep_ms);
      const double ms = median(total);
      std::printf(
          "      {\"wisps\": %d, \"outline_cubics\": %ld, \"segments\": %d, \"vertices\": %d, "
          "\"edges\": %d, \"faces\": %d, \"intersections\": %d, \"hidden_wisps\": %d, "
          "\"cull_ms\": %.2f,\n"
          "       \"build_wisps_ms\": %.2f, \"sweep_ms\": %.2f, \"resolve_ms\": %.2f, "
          "\"arrangement_ms\": %.2f, \"us_per_segment\": %.2f,\n"
          "       \"sweep_cpu_ms\": %.2f, \"arrangement_cpu_ms\": %.2f, \"cgal_sweep_ms\": %.2f, "
          "\"cgal_sweep_over_ours\": %.2f,\n"
          "       \"exact_bezier\": %s}%s\n",
          n, cubics, arr.stats.segments, arr.stats.vertices, arr.stats.edges, arr.stats.faces,
          arr.stats.intersections, arr.stats.hidden_wisps, median(cull), median(build),
          median(sweep), median(resolve), ms, 1000 * ms / arr.stats.segments, median(sweep_cpu),
          median(total_cpu), median(cgal_sweep), median(cgal_sweep) / median(sweep), exact.c_str(),
          s + 1 < sizes.size() ? "," : "");
      std::fflush(stdout);
    }
    std::printf("    ]}%s\n", k + 1 < scenes.size() ? "," : "");
  }
  std::printf("  ]\n}\n");
  return 0;
}

}  // namespace wisp::bench
