// What `wisp farm submit` hands to Slurm, as plain functions of the request (no cluster needed,
// so the tests check them directly): the frame ranges of the render tasks, cut at the renderer's
// warm-start blocks (render::block_aligned_ranges) so that the farm's pixels equal one machine's;
// each task's memory and time, from a per-frame cost measured on the default scene; and the three
// batch scripts (simulate once, the render array, the assembly) with the sbatch command lines that
// chain them. Everything a job reads or writes is under OUTDIR, by absolute path: the compute
// nodes must see OUTDIR, the scene and the wisp executable at the same paths (docs/farm.md).
#pragma once

#include <string>
#include <vector>

#include "apps/render/render_range.hpp"

namespace wisp::cli::farm {

// The cost of rendering one frame with one thread at a size, measured on the default scene
// (docs/farm.md has the table and how it was measured): wall seconds, and the resident memory of
// a render process (the animation and its projections) plus what one frame in flight adds.
struct FrameCost {
  double seconds = 0;
  double process_mb = 0;
  double frame_mb = 0;
};
FrameCost measured_frame_cost(int width, int height);

// What one render task asks Slurm for.
struct TaskResources {
  int cpus = 1;
  int mem_mb = 0;   // --mem
  int minutes = 0;  // --time
};

// A task rendering `frames` frames (in blocks of `block`) with `cpus` threads: memory for the
// process and one frame per thread, and the frames' time over the blocks rendered at once, both
// with margins (Slurm kills a task that exceeds either).
TaskResources task_resources(int width, int height, int frames, int block, int cpus);

struct SubmitRequest {
  std::string scene;          // absolute path of the scene file
  std::string outdir;         // absolute path of the output folder
  std::string wisp;           // absolute path of the wisp executable the jobs run
  int width = 0, height = 0;  // the image size (the scene camera's unless --size)
  bool size_given = false;    // pass --size to the render tasks
  int shards = 0;             // number of render tasks (0: from frames_per_task, or 4)
  int frames_per_task = 0;    // frames per task, rounded up to whole warm-start blocks
  int throttle = 0;           // at most this many tasks at once (sbatch --array=...%M); 0: no limit
  int cpus = 1;               // threads per task (--cpus-per-task)
  std::string partition;      // empty: the cluster's default
  std::vector<std::string> sbatch_args;  // passed to every sbatch call, after ours
};

// One job to submit: its batch script and where it goes.
struct BatchJob {
  std::string name;    // "simulate", "render", "assemble"
  std::string script;  // the text of the batch script
  std::string path;    // OUTDIR/farm/<name>.sbatch
};

struct FarmPlan {
  std::vector<render::FrameRange> ranges;  // task i renders ranges[i]
  TaskResources task;
  BatchJob simulate, render, assemble;
};

// The plan for an animation of `frame_count` frames in warm-start blocks of `block`. Throws
// std::invalid_argument naming the option when shards or frames_per_task are out of range.
FarmPlan plan_farm(const SubmitRequest& request, int frame_count, int block);

// The array specification of some tasks: "0-3", "1,3" or "5", with "%M" when throttled.
std::string array_spec(const std::vector<int>& tasks, int throttle);

// sbatch's arguments (after "sbatch") to submit `job`: --parsable, the dependency and the array
// when given, the request's extra arguments, the script.
std::vector<std::string> sbatch_args(const SubmitRequest& request, const BatchJob& job,
                                     const std::string& dependency, const std::string& array);

// `text` quoted for bash when it holds anything but [A-Za-z0-9_./:=%+,-].
std::string shell_quote(const std::string& text);

// The log file of a job: OUTDIR/logs/simulate.log, render_<task>.log, assemble.log.
std::string log_path(const std::string& outdir, const std::string& job, int task = -1);

}  // namespace wisp::cli::farm
