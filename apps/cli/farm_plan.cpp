// The jobs of `wisp farm submit` (see farm_plan.hpp).
#include "apps/cli/farm_plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wisp::cli::farm {
namespace {

// One thread rendering the whole default scene (data/scenes/default.json, 97 frames) on the
// development machine, `wisp render --threads 1 --size WxH`: mean seconds per frame (stats.json)
// and the process's peak resident memory (/usr/bin/time %M), on a machine shared with other work
// (a loaded figure errs on the safe side). docs/farm.md has the table and how to measure again.
struct Measured {
  double pixels, seconds, peak_mb;
};
constexpr Measured kMeasured[] = {
    {128.0 * 128, 0.49, 209},
    {512.0 * 512, 1.41, 231},
    {1024.0 * 1024, 2.68, 420},
    {2048.0 * 2048, 5.60, 1064},
};
constexpr int kMeasuredCount = int(sizeof kMeasured / sizeof kMeasured[0]);

// Linear in the pixel count between measured sizes, and beyond the last two (per-frame cost
// grows with the pixels once the geometry's fixed part is paid); the smallest size's below.
double interpolate(double pixels, double Measured::*field) {
  int i = 1;
  while (i < kMeasuredCount - 1 && pixels > kMeasured[i].pixels) ++i;
  const Measured &a = kMeasured[i - 1], &b = kMeasured[i];
  const double t = (std::max(pixels, kMeasured[0].pixels) - a.pixels) / (b.pixels - a.pixels);
  return a.*field + t * (b.*field - a.*field);
}

// Characters bash takes literally outside quotes.
bool plain(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) ||
         std::string("_./:=%+,-").find(c) != std::string::npos;
}

std::string join_quoted(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + shell_quote(w);
  return out;
}

// The #SBATCH lines every job has.
std::string header(const SubmitRequest& r, const std::string& name, const std::string& log) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "#SBATCH --job-name=wisp-" << name << "\n"
    << "#SBATCH --output=" << log << "\n"
    << "#SBATCH --open-mode=append\n"
    << "#SBATCH --chdir=" << r.outdir << "\n";
  if (!r.partition.empty()) s << "#SBATCH --partition=" << r.partition << "\n";
  return s.str();
}

std::string simulate_script(const SubmitRequest& r) {
  std::ostringstream s;
  s << header(r, "simulate", log_path(r.outdir, "simulate")) << "#SBATCH --cpus-per-task=1\n"
    << "# wisp farm: simulate the scene once; the render tasks read the animation.\n"
    << "set -euo pipefail\n"
    << "echo \"wisp farm: simulate on $(hostname) at $(date -Is)\"\n"
    << "exec " << join_quoted({r.wisp, "simulate", r.scene, "-o", r.outdir + "/anim.wsim", "-q"})
    << "\n";
  return s.str();
}

std::string render_script(const SubmitRequest& r, const std::vector<render::FrameRange>& ranges,
                          const TaskResources& task) {
  std::ostringstream s;
  s << header(r, "render", r.outdir + "/logs/render_%a.log")
    << "#SBATCH --cpus-per-task=" << task.cpus << "\n"
    << "#SBATCH --mem=" << task.mem_mb << "M\n"
    << "#SBATCH --time=" << task.minutes << "\n"
    << "# wisp farm: array task i renders frames ranges[i] (whole warm-start blocks); frames\n"
    << "# already in the folder are skipped, so a task run again resumes.\n"
    << "set -euo pipefail\n"
    << "ranges=(";
  for (size_t i = 0; i < ranges.size(); ++i)
    s << (i ? " " : "") << ranges[i].first << ":" << ranges[i].last;
  std::vector<std::string> render = {
      r.wisp, "render", r.scene, "-o", r.outdir, "--anim", r.outdir + "/anim.wsim"};
  if (r.size_given)
    render.insert(render.end(),
                  {"--size", std::to_string(r.width) + "x" + std::to_string(r.height)});
  s << ")\n"
    << "task=$SLURM_ARRAY_TASK_ID\n"
    << "echo \"wisp farm: task $task, frames ${ranges[$task]}, on $(hostname) at $(date -Is)\"\n"
    << "exec " << join_quoted(render) << " --frames \"${ranges[$task]}\""
    << " --threads \"${SLURM_CPUS_PER_TASK:-1}\" --no-previews"
    << " --stats " << shell_quote(r.outdir + "/stats") << "/task_\"$task\".json -q\n";
  return s.str();
}

std::string assemble_script(const SubmitRequest& r) {
  std::ostringstream s;
  s << header(r, "assemble", log_path(r.outdir, "assemble")) << "#SBATCH --cpus-per-task=1\n"
    << "# wisp farm: preview video, contact sheet and one stats.json from every task's frames.\n"
    << "set -euo pipefail\n"
    << "echo \"wisp farm: assemble on $(hostname) at $(date -Is)\"\n"
    << "exec " << join_quoted({r.wisp, "assemble", r.outdir, "-q"}) << "\n";
  return s.str();
}

}  // namespace

FrameCost measured_frame_cost(int width, int height) {
  const double pixels = double(width) * height;
  const double peak = interpolate(pixels, &Measured::peak_mb);
  // The smallest size's peak is nearly all process (animation, projections, libraries); what
  // the larger sizes add is the frame in flight.
  const double process = kMeasured[0].peak_mb;
  return {interpolate(pixels, &Measured::seconds), process, std::max(0.0, peak - process)};
}

TaskResources task_resources(int width, int height, int frames, int block, int cpus) {
  const FrameCost cost = measured_frame_cost(width, height);
  TaskResources t;
  t.cpus = std::max(1, cpus);
  // Threads work on whole blocks: no more of them at once than the task has blocks.
  const int blocks = (frames + block - 1) / std::max(1, block);
  const int parallel = std::max(1, std::min(t.cpus, blocks));
  // Memory: 1.5x the measured peak (scenes differ; Slurm kills a task over its limit), in
  // 64 MB steps.
  const double mb = 1.5 * (cost.process_mb + cost.frame_mb * parallel);
  t.mem_mb = int(std::ceil(mb / 64.0)) * 64;
  // Time: the frames in sequence over the parallel blocks, a resumed block's earlier frames
  // solved again, reading the animation; 3x that (busier nodes, slower cores) plus 5 minutes.
  const double seconds = cost.seconds * (double(frames) / parallel + block) + 10;
  t.minutes = int(std::ceil(3 * seconds / 60.0)) + 5;
  return t;
}

FarmPlan plan_farm(const SubmitRequest& r, int frame_count, int block) {
  block = std::max(1, block);
  const int blocks = (frame_count + block - 1) / block;
  if (r.shards < 0) throw std::invalid_argument("--shards: must be at least 1");
  if (r.frames_per_task < 0) throw std::invalid_argument("--frames-per-task: must be at least 1");
  int parts = r.shards;
  if (parts == 0 && r.frames_per_task > 0) {
    const int blocks_per_task = (r.frames_per_task + block - 1) / block;
    parts = (blocks + blocks_per_task - 1) / blocks_per_task;
  }
  if (parts == 0) parts = 4;
  FarmPlan plan;
  plan.ranges = render::block_aligned_ranges(frame_count, block, parts);
  int longest = 0;
  for (const render::FrameRange& range : plan.ranges) longest = std::max(longest, range.size());
  plan.task = task_resources(r.width, r.height, longest, block, r.cpus);
  const std::string dir = r.outdir + "/farm/";
  plan.simulate = {"simulate", simulate_script(r), dir + "simulate.sbatch"};
  plan.render = {"render", render_script(r, plan.ranges, plan.task), dir + "render.sbatch"};
  plan.assemble = {"assemble", assemble_script(r), dir + "assemble.sbatch"};
  return plan;
}

std::string array_spec(const std::vector<int>& tasks, int throttle) {
  std::string spec;
  for (size_t i = 0; i < tasks.size();) {
    size_t j = i;
    while (j + 1 < tasks.size() && tasks[j + 1] == tasks[j] + 1) ++j;
    spec += (spec.empty() ? "" : ",") + std::to_string(tasks[i]);
    if (j > i) spec += "-" + std::to_string(tasks[j]);
    i = j + 1;
  }
  if (throttle > 0) spec += "%" + std::to_string(throttle);
  return spec;
}

std::vector<std::string> sbatch_args(const SubmitRequest& r, const BatchJob& job,
                                     const std::string& dependency, const std::string& array) {
  std::vector<std::string> args = {"--parsable"};
  if (!dependency.empty()) args.push_back("--dependency=" + dependency);
  if (!array.empty()) args.push_back("--array=" + array);
  args.insert(args.end(), r.sbatch_args.begin(), r.sbatch_args.end());
  args.push_back(job.path);
  return args;
}

std::string shell_quote(const std::string& text) {
  if (!text.empty() && std::all_of(text.begin(), text.end(), plain)) return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string log_path(const std::string& outdir, const std::string& job, int task) {
  return outdir + "/logs/" + job + (task >= 0 ? "_" + std::to_string(task) : "") + ".log";
}

}  // namespace wisp::cli::farm
