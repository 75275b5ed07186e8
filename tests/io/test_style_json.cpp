// The scene's style part with presets, ramps and ink, and ink strokes as constant-width pieces.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "apps/render/picture.hpp"
#include "io/ramp_file.hpp"
#include "io/scene.hpp"
#include "tests/test_folder.hpp"
#include "vector/toon_ramp.hpp"

using nlohmann::json;
using wisp::io::parse_scene;
namespace fs = std::filesystem;

namespace {

std::string error_of(const json& doc, const fs::path& path = "scene.json") {
  try {
    parse_scene(doc, path);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

fs::path temp_dir(const std::string& name) {
  return wisp::test::fresh_folder("style_json_" + name);
}

}  // namespace

TEST_CASE("every preset in data/styles loads, and scene fields override it", "[io][style]") {
  for (const std::string p : {"faraj", "toon", "anime", "soft", "hatch"}) {
    INFO(p);
    const auto s = parse_scene({{"style", {{"preset", p}}}}, "scene.json");
    CHECK((s.style.shading.model == wisp::vector::ShadingModel::Faraj) == (p == "faraj"));
  }
  const auto faraj = parse_scene({{"style", {{"preset", "faraj"}}}}, "scene.json");
  const auto plain = parse_scene(json::object(), "scene.json");
  CHECK(faraj.style.hair == plain.style.hair);  // faraj is the default look
  CHECK(!faraj.style.ink.enabled());

  const auto toon = parse_scene({{"style", {{"preset", "toon"}}}}, "scene.json");
  REQUIRE(toon.style.shading.ramp);
  CHECK(toon.style.shading.ramp->width > 0);
  CHECK(toon.style.shading.metric == wisp::vector::RampMetric::Depth);
  CHECK(toon.style.specular.shape == wisp::vector::HighlightShape::Band);
  CHECK(toon.style.ink.silhouette_width > toon.style.ink.occlusion_width);
  CHECK(wisp::vector::RampBands(*toon.style.shading.ramp, toon.style.shading.band_threshold)
            .edges()
            .size() == 2);
  CHECK(!toon.style.hatching.enabled);
  const auto hatch = parse_scene(
      {{"style",
        {{"preset", "hatch"}, {"hatching", {{"tones", {0.7, 0.4}}, {"coverage", {0.1, 0.3}}}}}}},
      "scene.json");
  CHECK(hatch.style.hatching.enabled);
  CHECK(hatch.style.hatching.tones == std::vector<double>{0.7, 0.4});
  CHECK(hatch.style.hatching.length == 0.09);  // the preset's, kept

  // Fields override the preset whatever their order; nested objects merge field by field.
  const auto mine = parse_scene(json::parse(R"({"style": {
      "ink": {"silhouette_width": 7}, "hair_color": [1, 0, 0], "preset": "toon",
      "shading": {"ramp": null}}})"),
                                "scene.json");
  CHECK(mine.style.ink.silhouette_width == 7);
  CHECK(mine.style.ink.occlusion_width == toon.style.ink.occlusion_width);
  CHECK(mine.style.hair == Eigen::Vector3f(1, 0, 0));
  CHECK(!mine.style.shading.ramp);
  CHECK(mine.style.shading.model == wisp::vector::ShadingModel::Lit);
}

TEST_CASE("a preset file next to the scene, ramps relative to the file naming them",
          "[io][style]") {
  const fs::path dir = temp_dir("preset");
  cv::Mat ramp(2, 4, CV_8UC3, cv::Scalar(10, 20, 30));
  ramp.at<cv::Vec3b>(0, 3) = cv::Vec3b(200, 200, 200);
  fs::create_directories(dir / "looks" / "ramps");
  REQUIRE(cv::imwrite((dir / "looks" / "ramps" / "r.png").string(), ramp));
  std::ofstream(dir / "looks" / "mine.json")
      << R"({"description": "test", "shading": {"model": "lit", "ramp": "ramps/r.png"}})";
  const auto s = parse_scene({{"style", {{"preset", "looks/mine.json"}}}}, dir / "scene.json");
  REQUIRE(s.style.shading.ramp);
  CHECK(s.style.shading.ramp->width == 4);
  CHECK(s.style.shading.ramp->height == 2);
  CHECK(s.style.shading.ramp->at(0, 0).isApprox(Eigen::Vector3f(30, 20, 10) / 255.0f));
  const wisp::vector::RampBands bands(*s.style.shading.ramp, 0.1);
  REQUIRE(bands.edges().size() == 1);
  CHECK(bands.edges()[0] == 0.75);
  // Inside a band the lookup never blends across the edge.
  CHECK(bands.lookup(0.74, 0.0).isApprox(Eigen::Vector3f(30, 20, 10) / 255.0f));
  CHECK(bands.band(0.74) == 0);
  CHECK(bands.band(0.75) == 1);

  // Errors inside a preset name the scene's field and the preset's own field.
  std::ofstream(dir / "looks" / "bad.json") << R"({"ink": {"silhouette_width": -1}})";
  CHECK_THAT(error_of({{"style", {{"preset", "looks/bad.json"}}}}, dir / "scene.json"),
             Catch::StartsWith((dir / "scene.json").string() + ": style.preset: ") &&
                 Catch::Contains("bad.json: ink.silhouette_width: must be a width"));
  std::ofstream(dir / "looks" / "nest.json") << R"({"preset": "toon"})";
  CHECK_THAT(error_of({{"style", {{"preset", "looks/nest.json"}}}}, dir / "scene.json"),
             Catch::Contains("nest.json: preset: unknown field"));
  fs::remove_all(dir);
}

TEST_CASE("bad style values name the field", "[io][style]") {
  const fs::path dir = temp_dir("bad");
  std::ofstream(dir / "zero.png");
  const fs::path scene = dir / "scene.json";
  CHECK_THAT(
      error_of({{"style", {{"shading", {{"ramp", "nothere.png"}}}}}}, scene),
      Catch::StartsWith(scene.string() + ": style.shading.ramp: " + (dir / "nothere.png").string() +
                        ": cannot open the ramp image: no such file"));
  CHECK_THAT(error_of({{"style", {{"shading", {{"ramp", "zero.png"}}}}}}, scene),
             Catch::Contains("style.shading.ramp: ") && Catch::Contains("not a PNG image"));
  CHECK_THAT(error_of({{"style", {{"shading", {{"ramp", 3}}}}}}),
             Catch::Contains("style.shading.ramp: expected an image file name or null"));
  CHECK(error_of({{"style", {{"ink", {{"silhouette_width", -1}}}}}}) ==
        "scene.json: style.ink.silhouette_width: must be a width in [0, 1000] pixels (0: no "
        "silhouette ink)");
  CHECK(error_of({{"style", {{"ink", {{"occlusion_widht", 1}}}}}}) ==
        "scene.json: style.ink.occlusion_widht: unknown field (did you mean \"occlusion_width\"?)");
  CHECK(error_of({{"style", {{"shadng", {{"model", "lit"}}}}}}) ==
        "scene.json: style.shadng: unknown field (did you mean \"shading\"?)");
  CHECK_THAT(error_of({{"style", {{"shading", {{"ramp_metric", "depht"}}}}}}),
             Catch::Contains("style.shading.ramp_metric: expected one of none, depth, back_light, "
                             "specular, got \"depht\" (did you mean \"depth\"?)"));
  CHECK_THAT(error_of({{"style", {{"highlights", {{"threshold", 1.5}}}}}}),
             Catch::Contains("style.highlights.threshold: must be in (0, 1)"));
  CHECK_THAT(error_of({{"style", {{"shading", {{"depth_near", 2}, {"depth_far", 1}}}}}}),
             Catch::Contains("style.shading.depth_far: must be greater than depth_near"));
  CHECK_THAT(error_of({{"style", {{"hatching", {{"tones", {0.3, 0.5, 0.6}}}}}}}),
             Catch::Contains("style.hatching.tones: must be descending, in (0, 1]"));
  CHECK_THAT(error_of({{"style", {{"hatching", {{"coverage", {0.1, 0.2}}}}}}}),
             Catch::Contains("style.hatching.coverage: must have one entry per tone level"));
  CHECK_THAT(error_of({{"style", {{"hatching", {{"tones", 0.5}}}}}}),
             Catch::Contains("style.hatching.tones: expected an array of numbers"));
  CHECK_THAT(error_of({{"style", {{"hatching", {{"body_tones", {0.3, "a"}}}}}}}),
             Catch::Contains("style.hatching.body_tones[1]: "));
  CHECK_THAT(error_of({{"style", {{"preset", 3}}}}), Catch::Contains("style.preset: expected"));
  CHECK_THAT(error_of({{"style", {{"preset", "sfot"}}}}),
             Catch::Contains("(did you mean \"soft\"?)"));
  fs::remove_all(dir);
}

TEST_CASE("ink strokes become constant-width pieces within half a step of the width",
          "[io][style]") {
  wisp::render::InkStroke s;
  // Two cubics along x, the width falling linearly from 4 to 0 over the path.
  s.curve.points = {{0, 0}, {10, 0}, {20, 0}, {30, 0}, {40, 0}, {50, 0}, {60, 0}};
  s.curve_width = {{0.0, 4.0}, {1.0, 0.0}};
  const double step = 0.25;
  const auto pieces = wisp::render::ink_pieces(s, step);
  REQUIRE(!pieces.empty());
  double prev_end = 0;
  for (const auto& p : pieces) {
    REQUIRE(p.piece_count() >= 1);
    REQUIRE(p.points.size() == 3 * size_t(p.piece_count()) + 1);
    CHECK(p.width > 0);
    // Where the piece lies, the exact width (4 - x / 15) is within half a step of its width.
    for (int i = 0; i < p.piece_count(); ++i)
      for (double x : {p.piece(i)[0].x(), p.piece(i)[3].x()}) {
        const double exact = 4 - x / 15;
        CHECK(std::abs(exact - p.width) <= step / 2 + step / 4);  // + the sub-interval's change
      }
    CHECK(p.points.front().x() >= prev_end - 1e-9);
    prev_end = p.points.back().x();
  }
  // Widths step down monotonically, and constant stretches are single pieces.
  for (size_t i = 1; i < pieces.size(); ++i) CHECK(pieces[i].width < pieces[i - 1].width);
  s.curve_width = {{0.0, 2.0}, {1.0, 2.0}};
  const auto constant = wisp::render::ink_pieces(s, step);
  REQUIRE(constant.size() == 1);
  CHECK(constant[0].points == s.curve.points);
  CHECK(constant[0].width == 2.0);
}
