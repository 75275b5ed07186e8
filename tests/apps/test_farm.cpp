// `wisp farm` without a cluster: the task ranges follow the renderer's warm-start blocks, the
// resources grow with the size, the batch scripts and sbatch lines of --dry-run say what they
// must, Slurm's answers parse, and a missing sbatch is one clear error. And `wisp assemble` on
// frames rendered in two ranges by hand: video, contact sheet and one merged stats.json.
// (tests/farm/ runs the farm on a real local cluster.)
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "apps/cli/farm_plan.hpp"
#include "apps/cli/slurm.hpp"
#include "io/video_file.hpp"
#include "run_command.hpp"

using namespace wisp::cli;
using wisp::render::FrameRange;
using wisp::test::fresh_folder;
using wisp::test::run_command;
namespace fs = std::filesystem;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";
const std::string kScene = WISP_SOURCE_DIR "/data/scenes/default.json";

farm::SubmitRequest request() {
  farm::SubmitRequest r;
  r.scene = "/data/my scene.json";
  r.outdir = "/shared/out";
  r.wisp = "/opt/wisp/bin/wisp";
  r.width = r.height = 512;
  r.size_given = true;
  return r;
}

}  // namespace

TEST_CASE("farm task ranges are whole warm-start blocks covering the animation", "[farm][cli]") {
  for (int frames : {1, 7, 8, 97, 1440})
    for (int block : {1, 8, 12})
      for (int parts : {1, 2, 4, 13, 200}) {
        INFO(frames << " frames, block " << block << ", " << parts << " parts");
        const auto ranges = wisp::render::block_aligned_ranges(frames, block, parts);
        const int blocks = (frames + block - 1) / block;
        CHECK(int(ranges.size()) == std::min(parts, blocks));
        int next = 0, smallest = frames, largest = 0;
        for (const FrameRange& r : ranges) {
          CHECK(r.first == next);
          CHECK(r.first % block == 0);
          CHECK(r.size() > 0);
          next = r.last;
          if (r.last != frames) {
            smallest = std::min(smallest, r.size());
            largest = std::max(largest, r.size());
          }
        }
        CHECK(next == frames);
        if (largest > 0) CHECK(largest - smallest <= block);
      }
  // --frames-per-task rounds up to whole blocks: 97 frames, blocks of 8, 10 per task -> 16.
  farm::SubmitRequest r = request();
  r.frames_per_task = 10;
  const farm::FarmPlan plan = farm::plan_farm(r, 97, 8);
  REQUIRE(plan.ranges.size() == 7);
  CHECK(plan.ranges[0].size() == 16);
  CHECK(plan.ranges.back().last == 97);
}

TEST_CASE("farm task resources come from the measured frame cost", "[farm][cli]") {
  const farm::TaskResources small = farm::task_resources(128, 128, 24, 8, 1);
  const farm::TaskResources large = farm::task_resources(2048, 2048, 24, 8, 1);
  const farm::TaskResources two = farm::task_resources(2048, 2048, 24, 8, 2);
  CHECK(small.mem_mb >= 1.5 * farm::measured_frame_cost(128, 128).process_mb);
  CHECK(large.mem_mb > small.mem_mb);
  CHECK(two.mem_mb > large.mem_mb);  // a second frame in flight
  CHECK(large.minutes > small.minutes);
  CHECK(two.minutes < large.minutes);  // blocks rendered two at a time
  CHECK(small.mem_mb % 64 == 0);
  // Between measured sizes the cost lies between theirs; beyond the largest it keeps growing.
  const double s1 = farm::measured_frame_cost(1024, 1024).seconds,
               s2 = farm::measured_frame_cost(1448, 1448).seconds,
               s3 = farm::measured_frame_cost(2048, 2048).seconds,
               s4 = farm::measured_frame_cost(4096, 4096).seconds;
  CHECK(s1 < s2);
  CHECK(s2 < s3);
  CHECK(s3 < s4);
}

TEST_CASE("farm batch scripts and sbatch lines", "[farm][cli]") {
  farm::SubmitRequest r = request();
  r.shards = 4;
  r.throttle = 2;
  r.partition = "render";
  r.sbatch_args = {"--account=vfx"};
  const farm::FarmPlan plan = farm::plan_farm(r, 97, 8);
  const std::string& render = plan.render.script;
  CHECK_THAT(render, Catch::Contains("ranges=(0:32 32:56 56:80 80:97)"));
  CHECK_THAT(render, Catch::Contains("#SBATCH --partition=render"));
  CHECK_THAT(render, Catch::Contains("#SBATCH --mem=" + std::to_string(plan.task.mem_mb) + "M"));
  CHECK_THAT(render, Catch::Contains("#SBATCH --time=" + std::to_string(plan.task.minutes)));
  CHECK_THAT(render, Catch::Contains("#SBATCH --output=/shared/out/logs/render_%a.log"));
  CHECK_THAT(render, Catch::Contains("/opt/wisp/bin/wisp render '/data/my scene.json' -o "
                                     "/shared/out --anim /shared/out/anim.wsim --size 512x512"));
  CHECK_THAT(render,
             Catch::Contains("--no-previews --stats /shared/out/stats/task_\"$task\".json"));
  CHECK_THAT(plan.simulate.script, Catch::Contains("simulate '/data/my scene.json' -o "
                                                   "/shared/out/anim.wsim"));
  CHECK_THAT(plan.assemble.script, Catch::Contains("/opt/wisp/bin/wisp assemble /shared/out"));
  CHECK(plan.render.path == "/shared/out/farm/render.sbatch");

  CHECK(farm::array_spec({0, 1, 2, 3}, 2) == "0-3%2");
  CHECK(farm::array_spec({1, 3, 4, 5, 9}, 0) == "1,3-5,9");
  const std::vector<std::string> args =
      farm::sbatch_args(r, plan.render, "afterok:12", farm::array_spec({0, 1, 2, 3}, 2));
  CHECK(args == std::vector<std::string>{"--parsable", "--dependency=afterok:12", "--array=0-3%2",
                                         "--account=vfx", "/shared/out/farm/render.sbatch"});
  CHECK(farm::shell_quote("it's") == "'it'\\''s'");
  CHECK(farm::shell_quote("") == "''");
  CHECK_THROWS_WITH(
      [] {
        farm::SubmitRequest bad = request();
        bad.shards = -1;
        farm::plan_farm(bad, 97, 8);
      }(),
      Catch::Contains("--shards"));
}

TEST_CASE("Slurm's answers parse", "[farm][cli]") {
  CHECK(slurm::parse_job_id("4242\n") == 4242);
  CHECK(slurm::parse_job_id("4242;cluster\n") == 4242);
  CHECK(slurm::parse_job_id("sbatch: error: invalid partition specified") == 0);
  const auto states = slurm::parse_job_states(
      "12|COMPLETED|None\n13_0|RUNNING|None\n13_1|PENDING|Dependency\n"
      "14|CANCELLED by 0\n");
  REQUIRE(states.size() == 4);
  CHECK(states.at("13_1").state == "PENDING");
  CHECK(states.at("13_1").reason == "Dependency");
  CHECK(states.at("12").reason.empty());
  CHECK(states.at("14").state == "CANCELLED");
  CHECK(slurm::failed_state("CANCELLED"));
  CHECK(slurm::failed_state("OUT_OF_MEMORY"));
  CHECK(!slurm::failed_state("COMPLETED"));
  CHECK(slurm::active_state("PENDING"));
}

TEST_CASE("wisp farm submit --dry-run prints the scripts and writes nothing", "[farm][cli]") {
  const std::string dir = fresh_folder("farm_dry") + "/out";
  const auto r = run_command("env PATH=/nonexistent " + kWisp + " farm submit " + kScene + " -o " +
                             dir + " --size 128x128 --shards 4 --throttle 3 --dry-run");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // The default scene: 97 frames in warm-start blocks of 8.
  CHECK_THAT(r.output, Catch::Contains("ranges=(0:32 32:56 56:80 80:97)"));
  CHECK_THAT(r.output, Catch::Contains("--array=0-3%3"));
  CHECK_THAT(r.output, Catch::Contains("'--dependency=afterok:<simulate>'"));
  CHECK_THAT(r.output, Catch::Contains("'--dependency=afterok:<render>'"));
  CHECK_THAT(r.output, Catch::Contains(kWisp + " assemble " + dir));
  CHECK_THAT(r.output, Catch::Contains("--size 128x128"));
  CHECK(!fs::exists(dir));

  // Without --dry-run and without Slurm: one line, exit code 2, nothing written.
  const auto no_slurm = run_command("env PATH=/nonexistent " + kWisp + " farm submit " + kScene +
                                    " -o " + dir + " --size 128x128");
  CHECK(no_slurm.exit_code == 2);
  CHECK_THAT(no_slurm.output, Catch::Contains("sbatch not found on PATH"));
  CHECK(std::count(no_slurm.output.begin(), no_slurm.output.end(), '\n') == 1);
  CHECK(!fs::exists(dir));
}

TEST_CASE("wisp assemble merges ranges rendered by hand into one folder", "[farm][cli]") {
  // A small scene of 25 frames, rendered by two "machines" into one folder.
  const std::string scene = WISP_SOURCE_DIR "/data/scenes/sim_small.json";
  const std::string dir = fresh_folder("farm_assemble");
  const std::string anim = dir + "/anim.wsim";
  fs::copy_file(wisp::test::simulated(scene), anim);
  // Nothing rendered yet: assemble names the missing frames.
  const auto early = run_command(kWisp + " assemble " + dir + " --scene " + scene + " -q");
  CHECK(early.exit_code == 2);
  CHECK_THAT(early.output, Catch::Contains("25 of 25 frames missing (0, 1, 2"));
  // Each machine a range and its own stats file, no previews.
  for (const char* part : {"0:12", "12:25"}) {
    const auto r = run_command(kWisp + " render " + scene + " -o " + dir + " --anim " + anim +
                               " --size 64x64 --frames " + part + " --no-previews --stats " + dir +
                               "/stats/" + std::string(part).substr(0, 2) + ".json -q");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  CHECK(!fs::exists(dir + "/contact.png"));
  CHECK(!fs::exists(dir + "/stats.json"));
  const auto r = run_command(kWisp + " assemble " + dir + " --scene " + scene + " -q");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(wisp::io::count_video_frames(dir + "/preview.mp4") == 25);
  CHECK(cv::imread(dir + "/contact.png").cols > 64);
  std::ifstream in(dir + "/stats.json");
  const auto stats = nlohmann::json::parse(in);
  CHECK(stats["frames"].size() == 25);
  CHECK(stats["rendered"] == 25);
  CHECK(stats["width"] == 64);
  CHECK(stats["runs"].size() == 2);
  CHECK(stats["range"] == nlohmann::json::array({0, 25}));
  for (int k = 0; k < 25; ++k) CHECK(stats["frames"][k]["frame"] == k);
  // A machine killed before writing its stats file: its frames' records are still beside them.
  fs::remove(dir + "/stats/12.json");
  REQUIRE(run_command(kWisp + " assemble " + dir + " --scene " + scene + " -q").exit_code == 0);
  std::ifstream again(dir + "/stats.json");
  const auto kept = nlohmann::json::parse(again);
  CHECK(kept["runs"].size() == 1);
  REQUIRE(kept["frames"].size() == 25);
  for (int k = 0; k < 25; ++k) CHECK(kept["frames"][k]["frame"] == k);
}
