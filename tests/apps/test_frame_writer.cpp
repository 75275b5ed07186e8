// The frame writer of `wisp render` (apps/render/frame_writer.hpp): jobs run in order on its
// thread, no more than its depth wait at once, and a job's error reaches the frame threads and the
// end of the run instead of being lost; end to end, a frame that cannot be written ends the render
// with one line and a non-zero exit.
#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/render/frame_writer.hpp"
#include "run_command.hpp"

using wisp::render::FrameWriter;
namespace fs = std::filesystem;

TEST_CASE("the frame writer runs jobs in order and holds at most its depth waiting", "[render]") {
  std::vector<int> order;
  std::atomic<int> pushed{0}, started{0};
  int most_waiting = 0;
  {
    FrameWriter writer(2);
    for (int i = 0; i < 20; ++i) {
      writer.push([&, i] {
        ++started;
        most_waiting = std::max(most_waiting, pushed.load() - started.load());
        order.push_back(i);
      });
      ++pushed;
    }
    writer.finish();
  }
  REQUIRE(order.size() == 20);
  for (int i = 0; i < 20; ++i) CHECK(order[i] == i);
  CHECK(most_waiting <= 2);
}

TEST_CASE("a failed write reaches the next hand-over and the end of the run", "[render]") {
  FrameWriter writer(1);
  int ran = 0;
  writer.push([&] { ++ran; });
  writer.push([] { throw std::runtime_error("out/frame_0001.png: cannot write"); });
  // The writer stops at the error, so the queue fills and a hand-over sees it.
  bool seen = false;
  try {
    for (int i = 0; i < 50; ++i) writer.push([&] { ++ran; });
  } catch (const std::runtime_error& e) {
    seen = std::string(e.what()) == "out/frame_0001.png: cannot write";
  }
  CHECK_THROWS_WITH(writer.finish(), "out/frame_0001.png: cannot write");
  CHECK(seen);
  CHECK(ran == 1);  // nothing after the failed job ran
}

TEST_CASE("wisp render fails with one line when a frame cannot be written", "[cli][render]") {
  const std::string dir = wisp::test::fresh_folder("render_write_error");
  fs::create_directories(dir + "/frame_0001.png/x");  // a folder where the PNG goes
  const auto r =
      wisp::test::run_command(std::string(WISP_BIN_DIR "/wisp") + " render " +
                              WISP_SOURCE_DIR "/data/scenes/default.json -o " + dir +
                              " --size 48x48 --frames 0:3 --force -q --anim " +
                              wisp::test::simulated(WISP_SOURCE_DIR "/data/scenes/default.json"));
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("frame_0001.png"));
  CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  CHECK(!fs::exists(dir + "/stats.json"));
}
