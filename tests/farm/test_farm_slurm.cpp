// `wisp farm` end to end on the local Slurm cluster of scripts/slurm-local (the ctest fixture
// starts it; SLURM_CONF points at it): the default scene at 128x128 in 4 render tasks, one of
// them cancelled with scancel while it renders, then `wisp farm resubmit`: every frame, the video,
// the contact sheet and the merged stats appear, and every PNG is byte-identical to one
// `wisp render` process. Every wait has a deadline.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "io/video_file.hpp"
#include "run_command.hpp"

using nlohmann::json;
using wisp::test::fresh_folder;
using wisp::test::run_command;
namespace fs = std::filesystem;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";
const std::string kScene = WISP_SOURCE_DIR "/data/scenes/default.json";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string frame(const std::string& dir, int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "/frame_%04d.png", k);
  return dir + buf;
}

json status(const std::string& dir) {
  const auto r = run_command(kWisp + " farm status " + dir + " --json 2>/dev/null");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return json::parse(r.output);
}

// Polls `done(status)` every 0.3 s; fails naming `what` and showing the farm's status and
// Slurm's queue after `seconds`.
json wait_for(const std::string& dir, const std::string& what, int seconds,
              const std::function<bool(const json&)>& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  for (;;) {
    const json s = status(dir);
    if (done(s)) return s;
    if (std::chrono::steady_clock::now() > deadline) {
      INFO(run_command(kWisp + " farm status " + dir).output);
      INFO(run_command("squeue -t all").output);
      FAIL("timed out after " << seconds << " s waiting for " << what);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
}

}  // namespace

TEST_CASE("wisp farm on a local Slurm cluster: cancel, resubmit, same pixels as one process",
          "[farm][slurm]") {
  const auto sinfo = run_command("timeout 10 sinfo -h -o '%R %T'");
  INFO("SLURM_CONF=" << (getenv("SLURM_CONF") ? getenv("SLURM_CONF") : "") << "\n" << sinfo.output);
  REQUIRE(sinfo.exit_code == 0);
  REQUIRE_THAT(sinfo.output,
               Catch::Contains("idle") || Catch::Contains("mix") || Catch::Contains("alloc"));

  const std::string base = fresh_folder("farm_slurm");
  const std::string dir = base + "/out";

  // A partition that does not exist: one line naming the ones that do.
  const auto bad = run_command(kWisp + " farm submit " + kScene + " -o " + dir +
                               " --size 128x128 --partition nosuch");
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.output, Catch::Contains("nosuch: no such partition") && Catch::Contains("debug"));
  CHECK(!fs::exists(dir + "/farm.json"));

  const auto submit = run_command(kWisp + " farm submit " + kScene + " -o " + dir +
                                  " --size 128x128 --shards 4 --throttle 2");
  INFO(submit.output);
  REQUIRE(submit.exit_code == 0);

  // Task 1 is cancelled while it renders, once it has written a frame.
  const json farm = json::parse(read_file(dir + "/farm.json"));
  REQUIRE(farm["tasks"].size() == 4);
  const std::string task1 = farm["tasks"][1]["job"];
  wait_for(dir, "task 1 running", 120, [](const json& s) {
    const json& t = s["tasks"][1];
    return (t["state"] == "RUNNING" && t["done"].get<int>() >= 1) || t["active"] == false;
  });
  REQUIRE(status(dir)["tasks"][1]["active"] == true);  // else it ended before it could be cancelled
  REQUIRE(run_command("scancel " + task1).exit_code == 0);

  // The reference: one process, same scene and size, while the farm's other tasks work.
  const std::string ref = base + "/ref";
  const auto one = run_command(kWisp + " render " + kScene + " -o " + ref + " --size 128x128 -q");
  INFO(one.output);
  REQUIRE(one.exit_code == 0);

  // The other tasks finish; task 1 is reported failed, with its log's last line; the assembly
  // can never run.
  json s = wait_for(dir, "every task to end", 150, [](const json& st) {
    for (const json& t : st["tasks"])
      if (t["active"] == true) return false;
    return true;
  });
  CHECK(s["tasks"][1]["failed"] == true);
  CHECK(s["tasks"][1]["state"] == "CANCELLED");
  CHECK_THAT(s["tasks"][1]["note"].get<std::string>(), Catch::Contains("CANCELLED"));
  CHECK(s["tasks"][1]["done"].get<int>() < 24);
  for (int t : {0, 2, 3}) CHECK(s["tasks"][t]["failed"] == false);
  CHECK(s["done"].get<int>() < 97);
  const auto text = run_command(kWisp + " farm status " + dir);
  CHECK_THAT(text.output, Catch::Contains("wisp farm resubmit"));

  const auto again = run_command(kWisp + " farm resubmit " + dir);
  INFO(again.output);
  REQUIRE(again.exit_code == 0);
  CHECK_THAT(again.output, Catch::Contains("resubmitted 1 tasks"));
  s = wait_for(dir, "the assembly", 150, [](const json& st) {
    return st["assemble"]["state"] == "COMPLETED" || st["assemble"]["failed"] == true;
  });
  INFO(read_file(dir + "/logs/assemble.log"));
  REQUIRE(s["assemble"]["state"] == "COMPLETED");
  CHECK(s["done"] == 97);

  for (int k = 0; k < 97; ++k) {
    INFO("frame " << k);
    REQUIRE(fs::exists(frame(dir, k)));
    CHECK(read_file(frame(dir, k)) == read_file(frame(ref, k)));
  }
  CHECK(wisp::io::count_video_frames(dir + "/preview.mp4") == 97);
  CHECK(cv::imread(dir + "/contact.png").cols > 128);
  const json stats = json::parse(read_file(dir + "/stats.json"));
  // The frames task 1 wrote before it was cancelled have no record (its stats file is written at
  // its end): they count as skipped.
  CHECK(stats["rendered"].get<int>() + stats["skipped"].get<int>() == 97);
  CHECK(stats["frames"].size() == stats["rendered"]);
  CHECK(stats["frames"].size() > 97 - 24);
  CHECK(stats["width"] == 128);
  CHECK(stats["runs"].size() == 4);  // task 1's file from its second run
  const json recorded = json::parse(read_file(dir + "/farm.json"));
  CHECK(recorded["resubmits"].size() == 1);
  CHECK(recorded["tasks"][1]["job"] != task1);
  CHECK_THAT(recorded["command"].dump(), Catch::Contains("--throttle"));
}
