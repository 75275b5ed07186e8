// `wisp diffuse` end to end: real drawings in, PNG out; bad input gives one line and exit 2.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "diffusion/render.hpp"
#include "io/drawing_xml.hpp"
#include "run_command.hpp"

using wisp::test::fresh_folder;
using wisp::test::run_command;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";
const std::string kData = WISP_SOURCE_DIR "/data/drawings/";

}  // namespace

// (No ';' in test names: ctest splits the name there and runs neither half.)
TEST_CASE("wisp diffuse renders every external drawing, unblurred ones exactly as solved",
          "[cli][diffuse]") {
  const std::string out = fresh_folder("diffuse_external");
  for (const char* name :
       {"bubble", "crane", "crane_ribbons", "drape", "ladybug", "pepper", "portal", "sunset"}) {
    INFO(name);
    const std::string xml = kData + "external/" + name + ".xml";
    const std::string png = out + "/" + name + ".png", stats = out + "/" + name + ".json";
    const auto r =
        run_command(kWisp + " diffuse " + xml + " -o " + png + " --size 256x256 --stats " + stats);
    REQUIRE(r.exit_code == 0);
    CHECK(r.output.find("skipped") == std::string::npos);  // every primitive is drawn
    const cv::Mat img = cv::imread(png, cv::IMREAD_COLOR);
    REQUIRE(img.rows == 256);
    REQUIRE(img.cols == 256);
    cv::Scalar mean, dev;
    cv::meanStdDev(img, mean, dev);
    CHECK(dev[0] + dev[1] + dev[2] > 10);  // a picture, not a flat fill

    std::ifstream in(stats);
    const auto j = nlohmann::json::parse(in);
    CHECK(j["solver"]["converged"] == true);
    CHECK(j["times_ms"]["total"].get<double>() > 0);

    // Where nothing is blurred, the PNG without anti-aliasing is the library's solve of the
    // drawing (curves, Poisson curves and meshes), rounded.
    const auto file = wisp::io::read_drawing_xml(xml);
    bool blurred = false;
    for (const auto& c : file.drawing.curves)
      for (const auto& b : c.blur) blurred = blurred || b.sigma > 0;
    if (blurred) continue;
    const std::string sharp_png = out + "/" + name + "_sharp.png";
    REQUIRE(run_command(kWisp + " diffuse " + xml + " -o " + sharp_png +
                        " --size 256x256 --no-antialias")
                .exit_code == 0);
    const cv::Mat sharp = cv::imread(sharp_png, cv::IMREAD_COLOR);
    wisp::diffusion::SolverOptions solver;  // wisp diffuse's default stopping rule
    solver.max_error = wisp::diffusion::kEightBitError;
    const auto u =
        wisp::diffusion::render_drawing(file.drawing, 256, 256, solver, nullptr, false).planes;
    const size_t n = 256 * 256;
    int differ = 0;
    for (size_t i = 0; i < n; ++i) {
      const cv::Vec3b px = sharp.at<cv::Vec3b>(int(i / 256), int(i % 256));
      for (int c = 0; c < 3; ++c)
        differ += std::abs(px[2 - c] - std::clamp(u[c * n + i], 0.0f, 1.0f) * 255.0f) > 0.51f;
    }
    CHECK(differ == 0);
  }
}

TEST_CASE("wisp diffuse writes the drawing's own size by default and honours --scale",
          "[cli][diffuse]") {
  const std::string out = fresh_folder("diffuse_size");
  REQUIRE(run_command(kWisp + " diffuse " + kData + "external/pepper.xml -o " + out + "/a.png")
              .exit_code == 0);
  CHECK(cv::imread(out + "/a.png").cols == 512);
  REQUIRE(run_command(kWisp + " diffuse " + kData + "external/pepper.xml -o " + out +
                      "/b.png --scale 0.25")
              .exit_code == 0);
  CHECK(cv::imread(out + "/b.png").cols == 128);
}

TEST_CASE("wisp diffuse rejects bad input with one line, exit code 2 and no output",
          "[cli][diffuse]") {
  const std::string out = fresh_folder("diffuse_bad");
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(out + "/" + name) << text;
    return out + "/" + name;
  };
  const std::string good = kData + "external/pepper.xml";
  const std::string points =
      "<control_points_set><control_point x=\"1\" y=\"2\"/><control_point x=\"3\" y=\"4\"/>"
      "<control_point x=\"5\" y=\"6\"/><control_point x=\"7\" y=\"NaN\"/></control_points_set>";
  const std::string colours =
      "<left_colors_set><left_color R=\"1\" G=\"2\" B=\"3\" globalID=\"0\"/>"
      "</left_colors_set><right_colors_set><right_color R=\"1\" G=\"2\" "
      "B=\"3\" globalID=\"0\"/></right_colors_set>";
  const struct {
    std::string args, expected;
  } cases[] = {
      {write("malformed.xml", "<!DOCTYPE SceneXML><scene image_width=\"4\">"), "malformed XML"},
      {write("nan.xml",
             "<!DOCTYPE SceneXML><scene image_width=\"64\" image_height=\"64\">"
             "<curve_set><curve>" +
                 points + colours + "</curve></curve_set></scene>"),
       "not a finite number"},
      {write("counts.xml",
             "<!DOCTYPE SceneXML><scene image_width=\"64\" image_height=\"64\">"
             "<curve_set nb_curves=\"2\"></curve_set></scene>"),
       "nb_curves=2 but 0"},
      {good + " --size 20000x100", "16384"},
      {good + " --size 0x100", "between 1 and"},
      {good + " --size big", "expected WxH"},
      {out + "/missing.xml", "cannot open"},
  };
  for (const auto& c : cases) {
    INFO(c.args);
    const auto r = run_command(kWisp + " diffuse " + c.args + " -o " + out + "/out.png");
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains(c.expected));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(out + "/out.png"));
  }
  // An unwritable destination: also a clear error and nothing left behind.
  const auto r = run_command(kWisp + " diffuse " + good + " -o " + out + "/no/such/dir/out.png");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("does not exist"));
}
