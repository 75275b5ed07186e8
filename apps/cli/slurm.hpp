// Talking to Slurm through its client commands (sbatch, squeue, sacct, sinfo, scancel), each run
// with a time limit so that an unreachable controller ends in an error, never a hang; and the
// parsing of their answers, as plain functions the tests call on sample text.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace wisp::cli::slurm {

// A command's exit status (124 when it timed out) and its stdout and stderr together.
struct Output {
  int status = -1;
  std::string text;
};

// Runs program with args (quoted for the shell) under `timeout`.
Output run(const std::string& program, const std::vector<std::string>& args, int timeout_s = 30);

// Whether `program` is an executable file in a folder of $PATH.
bool on_path(const std::string& program);

// The job id in `sbatch --parsable`'s answer ("123" or "123;cluster"); 0 when there is none.
long parse_job_id(const std::string& text);

// What Slurm says of a job or array task ("12" or "12_3").
struct JobState {
  std::string state;   // PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, ...
  std::string reason;  // why it waits (Dependency, DependencyNeverSatisfied, ...), may be empty
};

// Lines "id|state|reason" (squeue -o "%i|%T|%r") or "id|state" (sacct -P -o JobID,State): by
// id. sacct's "CANCELLED by 0" is kept as CANCELLED.
std::map<std::string, JobState> parse_job_states(const std::string& text);

// The states of these jobs ("12", "12_3") that Slurm still knows: squeue first (jobs in the
// controller's memory), then sacct for the others where accounting is on.
std::map<std::string, JobState> job_states(const std::vector<std::string>& ids);

// Whether a state is final and not success: the task must be run again.
bool failed_state(const std::string& state);
// Whether a state is waiting or working.
bool active_state(const std::string& state);

// The cluster's partitions (sinfo). Throws std::runtime_error with sinfo's message when the
// controller does not answer.
std::vector<std::string> partitions();

// The host names of the nodes of `partition` (the default one when empty).
std::vector<std::string> node_hosts(const std::string& partition);

}  // namespace wisp::cli::slurm
