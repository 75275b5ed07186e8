// Slurm's client commands, run and read (see slurm.hpp).
#include "apps/cli/slurm.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "apps/cli/farm_plan.hpp"

namespace wisp::cli::slurm {
namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep)) parts.push_back(part);
  return parts;
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  for (const std::string& line : split(text, '\n'))
    if (!trim(line).empty()) out.push_back(trim(line));
  return out;
}

}  // namespace

Output run(const std::string& program, const std::vector<std::string>& args, int timeout_s) {
  std::string command =
      "timeout -k 5 " + std::to_string(timeout_s) + " " + farm::shell_quote(program);
  for (const std::string& a : args) command += " " + farm::shell_quote(a);
  command += " 2>&1";
  Output out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + program);
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.text.append(buf, n);
  const int status = pclose(pipe);
  out.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  return out;
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  for (const std::string& dir : split(path ? path : "", ':'))
    if (!dir.empty() && access((dir + "/" + program).c_str(), X_OK) == 0) return true;
  return false;
}

long parse_job_id(const std::string& text) {
  const std::string t = trim(text);
  size_t n = 0;
  while (n < t.size() && std::isdigit(static_cast<unsigned char>(t[n]))) ++n;
  if (n == 0 || (n < t.size() && t[n] != ';')) return 0;
  return std::stol(t.substr(0, n));
}

std::map<std::string, JobState> parse_job_states(const std::string& text) {
  std::map<std::string, JobState> states;
  for (const std::string& line : lines(text)) {
    const std::vector<std::string> f = split(line, '|');
    if (f.size() < 2) continue;
    JobState s;
    s.state = split(trim(f[1]), ' ').empty() ? "" : split(trim(f[1]), ' ')[0];
    if (f.size() > 2 && trim(f[2]) != "None") s.reason = trim(f[2]);
    states[trim(f[0])] = s;
  }
  return states;
}

std::map<std::string, JobState> job_states(const std::vector<std::string>& ids) {
  std::map<std::string, JobState> states;
  if (ids.empty()) return states;
  // Every job of this user in the controller's memory (a list of ids fails whole when one of
  // them has been forgotten), one line per array task.
  const Output q = run("squeue", {"--me", "-h", "-r", "-t", "all", "-o", "%i|%T|%r"});
  if (q.status == 0) states = parse_job_states(q.text);
  std::vector<std::string> unknown;
  for (const std::string& id : ids)
    if (!states.count(id)) unknown.push_back(id);
  if (!unknown.empty() && on_path("sacct")) {
    std::string list;
    for (const std::string& id : unknown) list += (list.empty() ? "" : ",") + id;
    const Output a = run("sacct", {"-n", "-P", "-X", "-o", "JobID,State", "-j", list});
    if (a.status == 0)
      for (auto& [id, s] : parse_job_states(a.text)) states.emplace(id, s);
  }
  return states;
}

bool failed_state(const std::string& state) {
  for (const char* s : {"FAILED", "CANCELLED", "TIMEOUT", "OUT_OF_MEMORY", "NODE_FAIL", "PREEMPTED",
                        "BOOT_FAIL", "DEADLINE", "REVOKED"})
    if (state == s) return true;
  return false;
}

bool active_state(const std::string& state) {
  for (const char* s : {"PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "SUSPENDED", "REQUEUED",
                        "RESIZING", "SIGNALING", "STAGE_OUT"})
    if (state == s) return true;
  return false;
}

std::vector<std::string> partitions() {
  const Output out = run("sinfo", {"-h", "-o", "%R"});
  if (out.status != 0)
    throw std::runtime_error("sinfo failed (" + trim(out.text) +
                             "): is the Slurm controller up, and SLURM_CONF right?");
  return lines(out.text);
}

std::vector<std::string> node_hosts(const std::string& partition) {
  std::vector<std::string> args = {"-h", "-N", "-o", "%n"};
  if (!partition.empty()) args.insert(args.end(), {"-p", partition});
  const Output out = run("sinfo", args);
  return out.status == 0 ? lines(out.text) : std::vector<std::string>{};
}

}  // namespace wisp::cli::slurm
