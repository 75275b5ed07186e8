// `wisp simulate` and `wisp render` on a dense groom: a .hair model of thousands of strands
// with hair.guides renders, each wisp as wide as its clump, and the clump widths survive a saved
// animation.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/hair_file.hpp"
#include "run_command.hpp"

using wisp::test::fresh_folder;
using wisp::test::run_command;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";

// A scene of `guides` clumps of a 4000-strand .hair model (the procedural generator's hair, in
// metres), a short nod, in `dir`.
std::string dense_scene(const std::string& dir, int guides) {
  wisp::sim::HairParams groom;
  groom.count = 4000;
  groom.segments = 29;
  wisp::io::HairFile h;
  h.strands = wisp::sim::generate_hair(groom, wisp::sim::HeadShape(wisp::sim::HeadGeometry{}));
  wisp::io::write_hair_file(dir + "/dense.hair", h);
  const std::string scene = dir + "/scene.json";
  std::ofstream(scene) << R"({"hair": {"source": "hair", "file": "dense.hair", "guides": )"
                       << guides << R"(},
      "motion": {"preset": "nod", "duration": 0.25},
      "render": {"video": false}})";
  return scene;
}

int hair_pixels(const std::string& mask) {
  const cv::Mat m = cv::imread(mask, cv::IMREAD_GRAYSCALE);
  REQUIRE(!m.empty());
  return cv::countNonZero(m > 127);
}

}  // namespace

TEST_CASE("a scene with a dense .hair model and hair.guides renders its clumps as wisps",
          "[cli][render][clumps]") {
  const std::string dir = fresh_folder("dense_groom");
  const std::string scene = dense_scene(dir, 40);
  auto r = run_command(kWisp + " render " + scene + " -o " + dir + "/direct --size 128x128" +
                       " --frames 0:3 --masks -q");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const int covered = hair_pixels(dir + "/direct/mask_0000.png");
  CHECK(covered > 1500);

  // Through a saved animation: the same pixels, so the widths were saved with it.
  r = run_command(kWisp + " simulate " + scene + " -o " + dir + "/dense.wsim -q");
  REQUIRE(r.exit_code == 0);
  r = run_command(kWisp + " render " + scene + " -o " + dir + "/saved --size 128x128" +
                  " --frames 0:3 --anim " + dir + "/dense.wsim -q");
  REQUIRE(r.exit_code == 0);
  for (const char* f : {"/frame_0000.png", "/frame_0002.png"}) {
    const cv::Mat a = cv::imread(dir + "/direct" + f), b = cv::imread(dir + "/saved" + f);
    REQUIRE(!a.empty());
    REQUIRE(a.size() == b.size());
    CHECK(cv::norm(a, b, cv::NORM_INF) == 0);
  }

  // 40 wisps as wide as their clumps cover the hair that 40 default-width wisps leave bare.
  std::ofstream(dir + "/thin.json") << R"({"hair": {"source": "hair", "file": "dense.hair",
      "count": 40}, "motion": {"preset": "nod", "duration": 0.25}, "render": {"video": false}})";
  r = run_command(kWisp + " render " + dir + "/thin.json -o " + dir +
                  "/thin --size 128x128 --frames 0:1 --masks -q");
  REQUIRE(r.exit_code == 0);
  const int thin = hair_pixels(dir + "/thin/mask_0000.png");
  std::printf(
      "[measured] hair pixels at 128x128: 40 clump wisps %d, 40 guides of the style's "
      "width %d\n",
      covered, thin);
  CHECK(covered > 1.3 * thin);

  // A bad value is one line naming the file and the field, exit code 2.
  std::ofstream(dir + "/bad.json") << R"({"hair": {"source": "hair", "file": "dense.hair",
      "guides": -4}})";
  r = run_command(kWisp + " render " + dir + "/bad.json -o " + dir + "/bad -q");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("bad.json: hair.guides: must be in [0, 100000]") != std::string::npos);
}
