// Scene JSON: defaults, every part parsed, unknown fields with suggestions, bad values named.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "io/scene.hpp"

using nlohmann::json;
using wisp::io::parse_scene;

namespace {

std::string error_of(const json& doc) {
  try {
    parse_scene(doc, "scene.json");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("an empty scene takes every default", "[io][scene]") {
  const wisp::io::Scene s = parse_scene(json::object(), "dir/scene.json");
  CHECK(s.hair.count == 150);
  CHECK(s.hair.segments == 24);
  CHECK(s.sim.model == "dftl");
  CHECK(s.motion.preset == "turn");
  CHECK(s.camera.width == 800);
  CHECK(s.head.shape == "ellipsoid");
}

TEST_CASE("every part of a scene is read", "[io][scene]") {
  const json doc = json::parse(R"({
    "head": {"shape": "mesh", "mesh": "head.obj", "mesh_scale": 0.01, "shoulders": true},
    "hair": {"count": 12, "segments": 8, "style": "curly", "amplitude": 0.02, "seed": 5},
    "motion": {"preset": "keys", "duration": 2, "keys": [
        {"time": 0}, {"time": 1, "position": [0, 0.1, 0], "ypr_deg": [30, 0, 0]}]},
    "sim": {"model": "rope", "fps": 30, "wind": {"velocity": [1, 0, 0], "gust": 0.5}},
    "camera": {"eye": [0, 0, 2], "fov_deg": 40, "width": 320, "height": 240}
  })");
  const wisp::io::Scene s = parse_scene(doc, "dir/scene.json");
  CHECK(s.head.mesh == std::filesystem::path("dir/head.obj"));
  CHECK(s.head.mesh_scale == 0.01);
  CHECK(s.head.shoulders);
  CHECK(s.hair.count == 12);
  CHECK(s.hair.style == "curly");
  CHECK(s.hair.seed == 5);
  REQUIRE(s.motion.keys.size() == 2);
  CHECK(s.motion.keys[1].ypr_deg.x() == 30);
  CHECK(s.sim.model == "rope");
  CHECK(s.sim.wind.velocity.x() == 1);
  CHECK(s.camera.height == 240);
}

TEST_CASE("unknown fields are errors naming the field, with near-miss suggestions", "[io][scene]") {
  CHECK(error_of({{"hair", {{"cuont", 3}}}}) ==
        "scene.json: hair.cuont: unknown field (did you mean \"count\"?)");
  CHECK(error_of({{"sim", {{"wind", {{"gusts", 1}}}}}}) ==
        "scene.json: sim.wind.gusts: unknown field (did you mean \"gust\"?)");
  CHECK(error_of({{"haor", json::object()}}) ==
        "scene.json: haor: unknown field (did you mean \"hair\"?)");
  CHECK(error_of({{"hair", {{"zzzzzz", 1}}}}) == "scene.json: hair.zzzzzz: unknown field");
  CHECK(error_of({{"sim", {{"model", "ropes"}}}}).find("did you mean \"rope\"") !=
        std::string::npos);
}

TEST_CASE("bad values are errors naming the field", "[io][scene]") {
  CHECK(error_of({{"hair", {{"count", -5}}}}).find("scene.json: hair.count: must be at least 1") ==
        0);
  CHECK(error_of({{"hair", {{"count", 2.5}}}}).find("hair.count: expected an integer") !=
        std::string::npos);
  CHECK(error_of({{"hair", {{"length", 0}}}}).find("hair.length") != std::string::npos);
  CHECK(error_of({{"sim", {{"bend_stiffness", -1}}}}).find("sim.bend_stiffness") !=
        std::string::npos);
  CHECK(error_of({{"camera", {{"eye", {0, 0}}}}}).find("camera.eye: expected an array of 3") !=
        std::string::npos);
  CHECK(error_of({{"motion", {{"preset", "keys"}, {"keys", {{{"time", 1}}, {{"time", 0.5}}}}}}})
            .find("motion.keys[1].time: keyframe times must increase") != std::string::npos);
  CHECK(error_of({{"head", {{"shape", "mesh"}}}}).find("head.mesh") != std::string::npos);
  CHECK(error_of({{"hair", {{"source", "hair"}}}}).find("hair.file") != std::string::npos);
}

TEST_CASE("NaN in keyframes and malformed JSON are clear errors", "[io][scene]") {
  const auto dir = std::filesystem::temp_directory_path() / "wisp_test_scene_json";
  std::filesystem::create_directories(dir);
  const auto write = [&](const char* name, const char* text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  // JSON has no NaN: the literal is a parse error with its position, and an overflowing number
  // is refused by the parser too. (NaN from code is caught by sim::HeadMotion, see tests/sim.)
  const auto nan = write("nan.json", R"({"motion": {"preset": "keys", "keys": [{"time": NaN}]}})");
  CHECK_THROWS_WITH(wisp::io::load_scene(nan),
                    Catch::StartsWith(nan.string() + ": invalid JSON: parse error"));
  const auto inf =
      write("inf.json",
            R"({"motion": {"preset": "keys", "keys": [{"time": 0, "position": [1e999, 0, 0]}]}})");
  CHECK_THROWS_WITH(wisp::io::load_scene(inf), Catch::StartsWith(inf.string() + ": invalid JSON") &&
                                                   Catch::Contains("number overflow"));
  CHECK_THROWS_WITH(wisp::io::load_scene(dir / "missing.json"), Catch::Contains("cannot open"));
  // A scene naming a missing OBJ fails when its setup is loaded, naming the field and the file.
  const auto obj = write("obj.json", R"({"head": {"shape": "mesh", "mesh": "nothere.obj"}})");
  const wisp::io::Scene s = wisp::io::load_scene(obj);
  CHECK_THROWS_WITH(wisp::io::load_sim_setup(s),
                    Catch::Contains("head.mesh") && Catch::Contains("nothere.obj"));
  std::filesystem::remove_all(dir);
}
