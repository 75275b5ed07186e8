// `wisp farm submit|status|resubmit`: an animation rendered on a Slurm cluster. `submit` writes the
// three batch scripts of farm_plan.hpp into OUTDIR/farm/, submits them chained by dependencies
// (simulate -> render array -> assemble) and records job ids, ranges and the command line in
// OUTDIR/farm.json; `status` tells per task the frames in the folder and what Slurm says;
// `resubmit` runs again the tasks that failed or were cancelled (a task resumes: the frames it had
// written are skipped) and a new assembly after them. docs/farm.md is the user's guide.
#include <sys/statfs.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/commands.hpp"
#include "apps/cli/farm_plan.hpp"
#include "apps/cli/slurm.hpp"
#include "apps/render/image_size.hpp"
#include "apps/render/render_range.hpp"
#include "apps/render/scene_frames.hpp"
#include "apps/render/scene_setup.hpp"
#include "io/atomic_file.hpp"
#include "io/scene.hpp"
#include "sim/simulate.hpp"
#include "util/module.hpp"

namespace wisp::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct SubmitArgs {
  std::string scene, outdir, size, partition;
  std::vector<std::string> sbatch;
  int shards = 0, frames_per_task = 0, throttle = 0, cpus = 1;
  bool dry_run = false;
};

json read_farm(const fs::path& outdir) {
  const fs::path file = outdir / "farm.json";
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(outdir.string() +
                             ": no farm.json: not a folder of `wisp farm submit`");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(file.string() + ": not JSON (" + e.what() + ")");
  }
}

void write_farm(const fs::path& outdir, const json& farm) {
  io::write_text_atomically(outdir / "farm.json", farm.dump(2) + "\n");
}

std::string now_iso() {
  char buf[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&t));
  return buf;
}

// The last non-empty line of a log; empty when there is no such file.
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

// The filesystem type of `path` when it is one that only this machine sees; empty otherwise
// (network and cluster filesystems, and types we do not know).
std::string local_filesystem(const fs::path& path) {
  struct statfs st {};
  if (statfs(path.c_str(), &st) != 0) return "";
  const struct {
    unsigned long magic;
    const char* name;
  } local[] = {{0xEF53, "ext2/3/4"},  {0x58465342, "xfs"},     {0x9123683E, "btrfs"},
               {0x01021994, "tmpfs"}, {0x794C7630, "overlay"}, {0x2FC12FC1, "zfs"},
               {0xF2F52010, "f2fs"},  {0x858458F6, "ramfs"}};
  for (const auto& fs_type : local)
    if (static_cast<unsigned long>(st.f_type) == fs_type.magic) return fs_type.name;
  return "";
}

bool is_this_host(const std::string& host) {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  const std::string full(name), shortname = full.substr(0, full.find('.'));
  return host == "localhost" || host == full || host == shortname;
}

// Errors a submission can be told before anything is written: no Slurm, a partition that does
// not exist, an output folder that the compute nodes cannot see.
void check_cluster(const farm::SubmitRequest& r) {
  if (!slurm::on_path("sbatch"))
    throw std::runtime_error(
        "sbatch not found on PATH: wisp farm needs Slurm's client commands (Debian: slurm-client); "
        "on this machine a test cluster starts with scripts/slurm-local start");
  const std::vector<std::string> parts = slurm::partitions();
  if (!r.partition.empty() && std::find(parts.begin(), parts.end(), r.partition) == parts.end()) {
    std::string names;
    for (const std::string& p : parts) names += (names.empty() ? "" : ", ") + p;
    throw std::invalid_argument("--partition " + r.partition +
                                ": no such partition on this cluster (it has: " + names + ")");
  }
  // The jobs read and write OUTDIR on the compute nodes: a folder on a local disk of this
  // machine is invisible to every other node.
  fs::path existing = r.outdir;
  while (!fs::exists(existing) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  const std::string type = local_filesystem(existing);
  if (type.empty()) return;
  for (const std::string& host : slurm::node_hosts(r.partition))
    if (!is_this_host(host))
      throw std::runtime_error(
          r.outdir + ": on a local " + type + " filesystem of this machine, which node " + host +
          " cannot see: put OUTDIR (and the scene and wisp) on a filesystem that every compute "
          "node mounts at the same path (NFS, Lustre, GPFS, BeeGFS, CephFS); check with `df -T` "
          "here and `srun df -T <folder>` on a node");
}

// sbatch, returning the job id; a refusal is an error quoting sbatch.
std::string submit_job(const farm::SubmitRequest& r, const farm::BatchJob& job,
                       const std::string& dependency, const std::string& array) {
  const slurm::Output out = slurm::run("sbatch", farm::sbatch_args(r, job, dependency, array));
  const long id = slurm::parse_job_id(out.text);
  if (out.status != 0 || id == 0) {
    std::string text = out.text;
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    throw std::runtime_error("sbatch " + job.path + " failed: " + text);
  }
  return std::to_string(id);
}

void cancel(const std::vector<std::string>& ids) {
  if (!ids.empty()) slurm::run("scancel", ids);
}

// The request as recorded in farm.json (resubmit reuses it).
json request_json(const farm::SubmitRequest& r) {
  return {{"scene", r.scene},       {"outdir", r.outdir}, {"wisp", r.wisp},
          {"width", r.width},       {"height", r.height}, {"size_given", r.size_given},
          {"throttle", r.throttle}, {"cpus", r.cpus},     {"partition", r.partition},
          {"sbatch", r.sbatch_args}};
}

farm::SubmitRequest request_from(const json& f) {
  farm::SubmitRequest r;
  r.scene = f.at("scene");
  r.outdir = f.at("outdir");
  r.wisp = f.at("wisp");
  r.width = f.at("width");
  r.height = f.at("height");
  r.size_given = f.at("size_given");
  r.throttle = f.at("throttle");
  r.cpus = f.at("cpus");
  r.partition = f.at("partition");
  r.sbatch_args = f.at("sbatch").get<std::vector<std::string>>();
  return r;
}

void print_dry_run(const farm::SubmitRequest& r, const farm::FarmPlan& plan) {
  std::printf("# wisp farm submit --dry-run: %zu render tasks; each %d CPU, %d MB, %d min\n",
              plan.ranges.size(), plan.task.cpus, plan.task.mem_mb, plan.task.minutes);
  std::vector<int> all;
  for (size_t i = 0; i < plan.ranges.size(); ++i) all.push_back(int(i));
  const struct {
    const farm::BatchJob* job;
    std::string dependency, array;
  } jobs[] = {{&plan.simulate, "", ""},
              {&plan.render, "afterok:<simulate>", farm::array_spec(all, r.throttle)},
              {&plan.assemble, "afterok:<render>", ""}};
  for (const auto& j : jobs) {
    std::string line = "sbatch";
    for (const std::string& a : farm::sbatch_args(r, *j.job, j.dependency, j.array))
      line += " " + farm::shell_quote(a);
    std::printf("\n# ---- %s: %s\n%s", j.job->path.c_str(), line.c_str(), j.job->script.c_str());
  }
}

void run_submit(const SubmitArgs& a, const std::vector<std::string>& command) {
  farm::SubmitRequest r;
  io::Scene scene = io::load_scene(a.scene);
  r.scene = fs::absolute(a.scene).lexically_normal().string();
  r.outdir = fs::absolute(a.outdir).lexically_normal().string();
  while (r.outdir.size() > 1 && r.outdir.back() == '/') r.outdir.pop_back();
  // The dispatcher beside this wisp-farm: the jobs run `wisp simulate`, `wisp render`...
  r.wisp = (util::executable_dir() / "wisp").string();
  r.size_given = !a.size.empty();
  if (r.size_given) {
    std::tie(r.width, r.height) = render::parse_size("--size", a.size);
  } else {
    r.width = scene.camera.width;
    r.height = scene.camera.height;
  }
  r.shards = a.shards;
  r.frames_per_task = a.frames_per_task;
  r.throttle = a.throttle;
  r.cpus = a.cpus;
  r.partition = a.partition;
  r.sbatch_args = a.sbatch;
  const int frame_count = sim::animation_frame_count(render::load_sim_setup(scene));
  const farm::FarmPlan plan = farm::plan_farm(r, frame_count, scene.render.warm_start_block);
  if (a.dry_run) {
    print_dry_run(r, plan);
    return;
  }

  check_cluster(r);
  const fs::path out(r.outdir);
  if (fs::exists(out / "farm.json"))
    throw std::runtime_error(r.outdir +
                             ": holds a farm run already (farm.json): see `wisp farm status`, "
                             "`wisp farm resubmit`, or submit into another folder");
  for (const char* sub : {"farm", "logs", "stats"}) {
    std::error_code ec;
    fs::create_directories(out / sub, ec);
    if (!fs::is_directory(out / sub))
      throw std::runtime_error(r.outdir + ": cannot create the output folder");
  }
  for (const farm::BatchJob* job : {&plan.simulate, &plan.render, &plan.assemble})
    io::write_text_atomically(job->path, job->script);

  json f = request_json(r);
  f["command"] = command;
  f["submitted"] = now_iso();
  f["frames"] = frame_count;
  f["warm_start_block"] = scene.render.warm_start_block;
  f["task_resources"] = {
      {"cpus", plan.task.cpus}, {"mem_mb", plan.task.mem_mb}, {"minutes", plan.task.minutes}};
  std::vector<std::string> submitted;
  try {
    const std::string sim = submit_job(r, plan.simulate, "", "");
    submitted.push_back(sim);
    std::vector<int> all;
    for (size_t i = 0; i < plan.ranges.size(); ++i) all.push_back(int(i));
    const std::string array =
        submit_job(r, plan.render, "afterok:" + sim, farm::array_spec(all, r.throttle));
    submitted.push_back(array);
    const std::string assemble = submit_job(r, plan.assemble, "afterok:" + array, "");
    submitted.push_back(assemble);
    f["jobs"] = {{"simulate", sim}, {"render", json::array({array})}, {"assemble", assemble}};
    f["tasks"] = json::array();
    for (size_t i = 0; i < plan.ranges.size(); ++i)
      f["tasks"].push_back({{"frames", {plan.ranges[i].first, plan.ranges[i].last}},
                            {"job", array + "_" + std::to_string(i)}});
  } catch (...) {
    cancel(submitted);  // no half-chained run left behind
    throw;
  }
  f["resubmits"] = json::array();
  write_farm(out, f);
  std::printf(
      "farm: simulate job %s, render job %s (%zu tasks, each %d CPU, %d MB, %d min), assemble job "
      "%s\nfarm: wisp farm status %s\n",
      f["jobs"]["simulate"].get<std::string>().c_str(),
      f["jobs"]["render"][0].get<std::string>().c_str(), plan.ranges.size(), plan.task.cpus,
      plan.task.mem_mb, plan.task.minutes, f["jobs"]["assemble"].get<std::string>().c_str(),
      r.outdir.c_str());
}

// What farm status knows of one job or task.
struct Entry {
  std::string name, job, state, reason, log, note;
  int first = 0, last = 0, done = 0;  // tasks: frames and how many are in the folder
  bool failed = false, active = false;
};

struct FarmStatus {
  Entry simulate, assemble;
  std::vector<Entry> tasks;
  int frames = 0, done = 0;
};

// One job's state from Slurm, or from the folder when Slurm has forgotten it; a failed job's log's
// last line, or what its missing log means.
void judge(Entry& e, const std::map<std::string, slurm::JobState>& states, bool output_complete) {
  const auto it = states.find(e.job);
  if (it != states.end()) {
    e.state = it->second.state;
    e.reason = it->second.reason;
  } else {
    e.state = output_complete ? "DONE" : "UNKNOWN";
  }
  e.active = slurm::active_state(e.state);
  e.failed = !e.active && !output_complete &&
             (slurm::failed_state(e.state) || e.state == "UNKNOWN" || e.state == "COMPLETED");
  if (e.reason == "DependencyNeverSatisfied") e.failed = true;
  if (e.failed && !e.active) {
    if (!fs::exists(e.log))
      e.note = "no log " + e.log +
               ": the node could not write to OUTDIR; check that it is on a filesystem every "
               "compute node mounts at the same path";
    else
      e.note = last_line(e.log);
  }
}

FarmStatus farm_status(const fs::path& out, const json& f) {
  FarmStatus s;
  s.frames = f.at("frames");
  const std::string outdir = f.at("outdir");
  const auto job = [](const json& j) { return j.get<std::string>(); };
  std::vector<std::string> ids = {job(f["jobs"]["simulate"]), job(f["jobs"]["assemble"])};
  for (const json& t : f["tasks"]) ids.push_back(job(t["job"]));
  const std::map<std::string, slurm::JobState> states = slurm::job_states(ids);

  const auto entry = [](const std::string& name, const std::string& id, const std::string& log) {
    Entry e;
    e.name = name;
    e.job = id;
    e.log = log;
    return e;
  };
  s.simulate = entry("simulate", job(f["jobs"]["simulate"]), farm::log_path(outdir, "simulate"));
  judge(s.simulate, states, fs::exists(out / "anim.wsim"));
  for (size_t i = 0; i < f["tasks"].size(); ++i) {
    const json& t = f["tasks"][i];
    Entry e =
        entry("task " + std::to_string(i), job(t["job"]), farm::log_path(outdir, "render", int(i)));
    e.first = t["frames"][0];
    e.last = t["frames"][1];
    e.done = e.last - e.first - int(render::missing_frames(out, {e.first, e.last}).size());
    s.done += e.done;
    judge(e, states, e.done == e.last - e.first);
    // A task waiting on a simulation that failed will never run.
    if (e.active && s.simulate.failed) e.failed = true;
    s.tasks.push_back(e);
  }
  s.assemble = entry("assemble", job(f["jobs"]["assemble"]), farm::log_path(outdir, "assemble"));
  judge(s.assemble, states,
        fs::exists(out / "stats.json") && fs::exists(out / "contact.png") && s.done == s.frames);
  return s;
}

json status_json(const FarmStatus& s) {
  const auto entry = [](const Entry& e) {
    json j = {{"job", e.job},       {"state", e.state}, {"reason", e.reason}, {"failed", e.failed},
              {"active", e.active}, {"log", e.log},     {"note", e.note}};
    if (e.last > e.first) {
      j["frames"] = {e.first, e.last};
      j["done"] = e.done;
    }
    return j;
  };
  json tasks = json::array();
  for (const Entry& e : s.tasks) tasks.push_back(entry(e));
  return {{"frames", s.frames},
          {"done", s.done},
          {"simulate", entry(s.simulate)},
          {"tasks", tasks},
          {"assemble", entry(s.assemble)}};
}

void print_status(const fs::path& out, const FarmStatus& s) {
  int running = 0, failed = 0;
  for (const Entry& e : s.tasks) {
    running += e.state == "RUNNING" ? e.last - e.first - e.done : 0;
    failed += e.failed ? 1 : 0;
  }
  std::printf("%s: %d of %d frames done, %d being rendered, %d failed tasks\n",
              out.string().c_str(), s.done, s.frames, running, failed);
  const auto line = [](const Entry& e, const std::string& frames) {
    std::printf("  %-9s job %-10s %-10s%s%s\n", e.name.c_str(), e.job.c_str(), e.state.c_str(),
                frames.c_str(), e.reason.empty() ? "" : (" (" + e.reason + ")").c_str());
    if (!e.note.empty()) std::printf("            %s\n", e.note.c_str());
  };
  line(s.simulate, "");
  for (const Entry& e : s.tasks)
    line(e, " frames " + std::to_string(e.first) + ":" + std::to_string(e.last) + ", " +
                std::to_string(e.done) + " done");
  line(s.assemble, "");
  if (failed > 0 || s.simulate.failed || s.assemble.failed)
    std::printf("run again what failed: wisp farm resubmit %s\n", out.string().c_str());
}

void run_status(const std::string& outdir, bool as_json) {
  const fs::path out(outdir);
  const FarmStatus s = farm_status(out, read_farm(out));
  if (as_json)
    std::printf("%s\n", status_json(s).dump(2).c_str());
  else
    print_status(out, s);
}

void run_resubmit(const std::string& outdir, const std::vector<std::string>& command) {
  const fs::path out(outdir);
  json f = read_farm(out);
  const FarmStatus s = farm_status(out, f);
  const farm::SubmitRequest r = request_from(f);
  if (!slurm::on_path("sbatch"))
    throw std::runtime_error("sbatch not found on PATH: wisp farm needs Slurm's client commands");
  std::vector<int> tasks;
  std::vector<std::string> still_active;  // array jobs the new assembly also waits for
  for (size_t i = 0; i < s.tasks.size(); ++i) {
    if (s.tasks[i].failed)
      tasks.push_back(int(i));
    else if (s.tasks[i].active) {
      const std::string job = s.tasks[i].job.substr(0, s.tasks[i].job.find('_'));
      if (std::find(still_active.begin(), still_active.end(), job) == still_active.end())
        still_active.push_back(job);
    }
  }
  const bool redo_sim = s.simulate.failed;
  const bool redo_assemble = !tasks.empty() || redo_sim || s.assemble.failed;
  if (!redo_assemble) {
    std::printf("farm: nothing failed in %s; nothing to resubmit\n", outdir.c_str());
    return;
  }
  // The old assembly waits on an array that failed: it would never run.
  if (s.assemble.active) cancel({s.assemble.job});
  for (const Entry& e : s.tasks)
    if (e.failed && e.active) cancel({e.job});  // waiting on a failed simulation
  const farm::FarmPlan plan = [&] {
    farm::SubmitRequest p = r;
    p.shards = int(f["tasks"].size());
    return farm::plan_farm(p, f["frames"], f["warm_start_block"]);
  }();
  json record = {{"command", command}, {"time", now_iso()}, {"tasks", tasks}};
  std::string dependency;
  if (redo_sim) {
    const std::string sim = submit_job(r, plan.simulate, "", "");
    f["jobs"]["simulate"] = sim;
    record["simulate"] = sim;
    dependency = "afterok:" + sim;
  }
  std::string assemble_after;
  if (!tasks.empty()) {
    const std::string array =
        submit_job(r, plan.render, dependency, farm::array_spec(tasks, r.throttle));
    f["jobs"]["render"].push_back(array);
    record["render"] = array;
    for (int t : tasks) f["tasks"][t]["job"] = array + "_" + std::to_string(t);
    assemble_after = "afterok:" + array;
  } else if (redo_sim) {
    assemble_after = dependency;
  }
  for (const std::string& job : still_active)
    assemble_after += (assemble_after.empty() ? "" : ",") + ("afterany:" + job);
  const std::string assemble = submit_job(r, plan.assemble, assemble_after, "");
  f["jobs"]["assemble"] = assemble;
  record["assemble"] = assemble;
  f["resubmits"].push_back(record);
  write_farm(out, f);
  std::printf(
      "farm: resubmitted %s%zu tasks%s, assemble job %s\n", redo_sim ? "the simulation, " : "",
      tasks.size(),
      record.contains("render") ? (" as job " + record["render"].get<std::string>()).c_str() : "",
      assemble.c_str());
}

}  // namespace

void add_command(CLI::App& app, const std::vector<std::string>& command) {
  CLI::App* farm_cmd = add_subcommand(app, "farm");
  farm_cmd->require_subcommand(1);

  auto a = std::make_shared<SubmitArgs>();
  CLI::App* submit = farm_cmd->add_subcommand(
      "submit", "Submit simulate, a render job array and assemble, chained, to Slurm");
  submit->add_option("scene", a->scene, "Scene file (.json)")->required();
  submit->add_option("-o,--output", a->outdir, "Output folder, seen by every compute node")
      ->required();
  auto* shards = submit->add_option("--shards", a->shards, "Number of render tasks (default 4)")
                     ->check(CLI::Range(1, 100000));
  submit
      ->add_option("--frames-per-task", a->frames_per_task,
                   "Frames per render task, rounded up to whole warm-start blocks")
      ->check(CLI::Range(1, 1000000))
      ->excludes(shards);
  submit->add_option("--size", a->size, "Image size WxH (default: the scene camera's)");
  submit->add_option("--partition", a->partition, "Slurm partition (default: the cluster's)");
  submit->add_option("--throttle", a->throttle, "At most this many render tasks at once (%M)")
      ->check(CLI::Range(1, 100000));
  submit->add_option("--cpus-per-task", a->cpus, "Threads per render task (default 1)")
      ->check(CLI::Range(1, 256));
  submit
      ->add_option("--sbatch", a->sbatch,
                   "Extra argument for every sbatch call (repeat; e.g. --sbatch=--account=vfx)")
      ->allow_extra_args(false);
  submit->add_flag("--dry-run", a->dry_run, "Print the batch scripts and sbatch lines only");
  submit->callback([a, command] { run_submit(*a, command); });

  auto status_dir = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  CLI::App* status = farm_cmd->add_subcommand(
      "status", "Frames done, running and failed per task, from Slurm and the folder");
  status->add_option("outdir", *status_dir, "The folder given to farm submit")->required();
  status->add_flag("--json", *as_json, "As JSON");
  status->callback([status_dir, as_json] { run_status(*status_dir, *as_json); });

  auto resubmit_dir = std::make_shared<std::string>();
  CLI::App* resubmit = farm_cmd->add_subcommand(
      "resubmit", "Run again the tasks that failed or were cancelled, then assemble");
  resubmit->add_option("outdir", *resubmit_dir, "The folder given to farm submit")->required();
  resubmit->callback([resubmit_dir, command] { run_resubmit(*resubmit_dir, command); });
}

}  // namespace wisp::cli
