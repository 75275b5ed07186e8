// Scene JSON: defaults, every part parsed, unknown fields with suggestions, bad values named.

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <initializer_list>

#include "apps/render/scene_setup.hpp"
#include "io/scene.hpp"
#include "tests/test_folder.hpp"

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

// The choice field at `pointer` ("/sim/model") reads every value of E (listed by the caller) by
// its name, next to the fields in `with` that some values need; a misspelt name is one line
// listing the names, with the nearest one.
template <class E, class Get>
void check_choice_field(const std::string& pointer, Get get, std::initializer_list<E> all,
                        const json& with = json::object()) {
  const json::json_pointer at(pointer);
  for (const E value : all) {
    json doc = with;
    doc[at] = wisp::sim::choice_name(value);
    INFO(doc.dump());
    CHECK(get(parse_scene(doc, "scene.json")) == value);
  }
  const std::vector<std::string> names = wisp::sim::choice_names<E>();
  CHECK(names.size() == all.size());
  std::string list, field = pointer.substr(1);
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  std::replace(field.begin(), field.end(), '/', '.');
  json doc;
  doc[at] = names[0] + "s";
  CHECK(error_of(doc) == "scene.json: " + field + ": expected one of " + list + ", got \"" +
                             names[0] + "s\" (did you mean \"" + names[0] + "\"?)");
}

}  // namespace

TEST_CASE("an empty scene takes every default", "[io][scene]") {
  const wisp::io::Scene s = parse_scene(json::object(), "dir/scene.json");
  CHECK(s.hair.count == 150);
  CHECK(s.hair.segments == 24);
  CHECK(s.sim.model == wisp::sim::SimModel::Dftl);
  CHECK(s.motion.preset == wisp::sim::MotionPreset::Turn);
  CHECK(s.camera.width == 800);
  CHECK(s.head.shape == wisp::sim::HeadKind::Ellipsoid);
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
  CHECK(s.hair.style == wisp::sim::HairCurl::Curly);
  CHECK(s.hair.seed == 5);
  REQUIRE(s.motion.keys.size() == 2);
  CHECK(s.motion.keys[1].ypr_deg.x() == 30);
  CHECK(s.sim.model == wisp::sim::SimModel::Rope);
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

TEST_CASE("every choice reads by its name; a misspelt one lists the names", "[io][scene]") {
  using namespace wisp::sim;
  using wisp::io::Scene;
  namespace v = wisp::vector;
  check_choice_field("/head/shape", [](const Scene& s) { return s.head.shape; },
                     {HeadKind::Ellipsoid, HeadKind::Mesh}, {{"head", {{"mesh", "head.obj"}}}});
  check_choice_field("/hair/source", [](const Scene& s) { return s.hair.source; },
                     {HairSource::Procedural, HairSource::Json, HairSource::Hair},
                     {{"hair", {{"file", "strands"}}}});
  check_choice_field("/hair/style", [](const Scene& s) { return s.hair.style; },
                     {HairCurl::Straight, HairCurl::Wavy, HairCurl::Curly});
  check_choice_field("/motion/preset", [](const Scene& s) { return s.motion.preset; },
                     {MotionPreset::None, MotionPreset::Turn, MotionPreset::Nod,
                      MotionPreset::Shake, MotionPreset::Walk, MotionPreset::Keys},
                     {{"motion", {{"keys", {{{"time", 0}}}}}}});
  check_choice_field("/sim/model", [](const Scene& s) { return s.sim.model; },
                     {SimModel::Dftl, SimModel::Featherstone, SimModel::Rope});
  check_choice_field("/style/profile",
                     [](const Scene& s) { return s.style.geometry.profile.shape; },
                     {v::WidthProfile::Shape::Linear, v::WidthProfile::Shape::Shin});
  check_choice_field("/style/shading/model", [](const Scene& s) { return s.style.shading.model; },
                     {v::ShadingModel::Faraj, v::ShadingModel::Lit});
  check_choice_field("/style/shading/ramp_metric",
                     [](const Scene& s) { return s.style.shading.metric; },
                     {v::RampMetric::None, v::RampMetric::Depth, v::RampMetric::BackLight,
                      v::RampMetric::Specular});
  check_choice_field("/style/highlights/shape",
                     [](const Scene& s) { return s.style.specular.shape; },
                     {v::HighlightShape::None, v::HighlightShape::Band, v::HighlightShape::Anime});
  CHECK(error_of({{"style", {{"highlight_side", "up"}}}}) ==
        "scene.json: style.highlight_side: expected one of left, right, got \"up\"");
  CHECK(error_of({{"sim", {{"model", 2}}}}) == "scene.json: sim.model: expected a string, got 2");
}

TEST_CASE("range errors are the stage's validate() messages behind the file and the part",
          "[io][scene]") {
  CHECK(error_of({{"sim", {{"fps", 0}}}}) == "scene.json: sim.fps: must be in (0, 1000]");
  CHECK(error_of({{"sim", {{"wind", {{"gust_frequency", -1}}}}}}) ==
        "scene.json: sim.wind.gust_frequency: must be in [0, 1000] Hz");
  CHECK(error_of({{"hair", {{"source", "json"}, {"file", "s.json"}, {"count", -1}}}}) ==
        "scene.json: hair.count: must be >= 0 (0 = all strands), got -1");
  CHECK(error_of({{"head", {{"radii", {0.1, 0, 0.1}}}}}) ==
        "scene.json: head.radii: every radius must be in (0, 10] m");
  CHECK(error_of({{"motion", {{"preset", "keys"}}}}) ==
        "scene.json: motion.keys: preset \"keys\" needs at least one keyframe");
  CHECK(error_of({{"camera", {{"target", {0, 0, 1.1}}}}}) ==
        "scene.json: camera.target: must differ from camera.eye");
  CHECK(error_of({{"render", {{"warm_start_block", 0}}}}) ==
        "scene.json: render.warm_start_block: must be in [1, 100000] frames");
  CHECK(error_of({{"style", {{"highlights", {{"teeth", 17}}}}}}) ==
        "scene.json: style.highlights.teeth: must be in [1, 16]");
  CHECK(
      error_of({{"style",
                 {{"shading",
                   {{"model", "lit"}, {"ambient", 0}, {"kajiya_diffuse", 0}, {"lambert", 0}}}}}}) ==
      "scene.json: style.shading: lit shading needs a positive ambient, kajiya_diffuse or "
      "lambert weight");
}

TEST_CASE("the lens and the style's blur are read, off by default, and checked", "[io][scene]") {
  const auto plain = parse_scene(json::object(), "scene.json");
  CHECK(plain.camera.aperture == 0);
  CHECK(plain.camera.focus_distance == 0);
  CHECK(plain.style.blur.tip == 0);
  CHECK(plain.style.blur.shutter == 0);
  const auto s = parse_scene(json::parse(R"({"camera": {"aperture": 0.08, "focus_distance": 0.9},
      "style": {"blur": {"tip": 3, "tip_fade": 0.2, "shutter": 0.5, "max": 12}}})"),
                             "scene.json");
  CHECK(s.camera.aperture == 0.08);
  CHECK(s.camera.focus_distance == 0.9);
  CHECK(s.style.blur.tip == 3);
  CHECK(s.style.blur.tip_fade == 0.2);
  CHECK(s.style.blur.shutter == 0.5);
  CHECK(s.style.blur.max == 12);
  CHECK(error_of({{"camera", {{"aperture", -0.1}}}}) ==
        "scene.json: camera.aperture: must be in [0, 1] m (the lens's diameter; 0: a pinhole, all "
        "in focus)");
  CHECK(error_of({{"camera", {{"focus_distance", -1}}}}) ==
        "scene.json: camera.focus_distance: must be in [0, 1000] m (0: the target's distance)");
  CHECK(error_of({{"style", {{"blur", {{"tip_fade", 0}}}}}}) ==
        "scene.json: style.blur.tip_fade: must be in (0, 1] (a fraction of the strand)");
  CHECK(error_of({{"style", {{"blur", {{"shutter", 2}}}}}}) ==
        "scene.json: style.blur.shutter: must be in [0, 1] (a fraction of a frame; 0: no motion "
        "blur)");
  CHECK(error_of({{"style", {{"blur", {{"tips", 2}}}}}}) ==
        "scene.json: style.blur.tips: unknown field (did you mean \"tip\"?)");
}

TEST_CASE("bad values are errors naming the field", "[io][scene]") {
  CHECK(error_of({{"hair", {{"count", -5}}}}).find("scene.json: hair.count: must be >= 0") == 0);
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
  CHECK(error_of({{"hair", {{"guides", -1}}}}) ==
        "scene.json: hair.guides: must be in [0, 100000] (0: every strand is a guide), got -1");
  CHECK(error_of({{"hair", {{"guides", "many"}}}}) ==
        "scene.json: hair.guides: expected an integer, got \"many\"");
  CHECK(error_of({{"hair", {{"guides", 10}, {"count", 100000}, {"segments", 999}}}})
            .find("scene.json: hair.count: a dense model (with guides) has at most 2e7") == 0);
  CHECK(parse_scene({{"hair", {{"guides", 40}}}}, "scene.json").hair.guides == 40);
}

TEST_CASE("NaN in keyframes and malformed JSON are clear errors", "[io][scene]") {
  const auto dir = wisp::test::test_folder("scene_json");
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
  CHECK_THROWS_WITH(wisp::render::load_sim_setup(s),
                    Catch::Contains("head.mesh") && Catch::Contains("nothere.obj"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("style, light and render parts fill the look of a scene", "[io][scene]") {
  const wisp::io::Scene d = parse_scene(json::object(), "scene.json");
  const wisp::vector::HairStyle style_defaults;
  CHECK(d.style.geometry.width == style_defaults.geometry.width);
  CHECK(d.style.hair == style_defaults.hair);
  CHECK(d.light_dir.isApprox(wisp::sim::default_light_dir()));
  CHECK(d.light_dir.norm() == Approx(1));
  CHECK(d.render.body);
  CHECK(d.render.torso);
  CHECK(d.render.solver_tolerance == 1e-4);
  CHECK(d.render.warm_start_block == 8);
  CHECK(d.render.video);
  CHECK(d.render.contact_sheet_columns == 6);
  CHECK(d.render.antialias);

  const json doc = json::parse(R"({
    "style": {"width": 0.02, "profile": "sine", "curvature_clamp": 0.5, "flatten_tolerance": 0.2,
              "hair_color": [0.9, 0.8, 0.1], "shadow_color": [0, 0, 0],
              "highlight_color": [1, 1, 1], "highlight_along": 0.6, "highlight_spread": 0.1,
              "highlight_side": "right"},
    "light": {"direction": [0, 3, 4]},
    "render": {"background_color": [1, 1, 1], "skin_color": [0.5, 0.4, 0.3], "body": false,
               "torso": false, "solver_tolerance": 1e-3, "warm_start_block": 3, "video": false,
               "contact_sheet_columns": 4, "antialias": false}
  })");
  const wisp::io::Scene s = parse_scene(doc, "scene.json");
  CHECK(s.style.geometry.width == 0.02);
  CHECK(s.style.geometry.profile.shape == wisp::vector::WidthProfile::Shape::Shin);
  CHECK(s.style.geometry.curvature_clamp == 0.5);
  CHECK(s.style.geometry.flatten_tolerance_px == 0.2);
  CHECK(error_of({{"style", {{"flatten_tolerance", 0}}}}) ==
        "scene.json: style.flatten_tolerance: must be in [0.005, 2] pixels");
  CHECK(s.style.hair == Eigen::Vector3f(0.9f, 0.8f, 0.1f));
  CHECK(s.style.shadow == Eigen::Vector3f::Zero());
  CHECK(s.style.highlight == Eigen::Vector3f::Ones());
  CHECK(s.style.highlight_along == 0.6);
  CHECK(s.style.highlight_spread == 0.1);
  CHECK(!s.style.highlight_on_left);
  CHECK(s.light_dir.isApprox(Eigen::Vector3d(0, 0.6, 0.8)));
  CHECK(s.render.background_color == Eigen::Vector3f::Ones());
  CHECK(s.render.skin_color == Eigen::Vector3f(0.5f, 0.4f, 0.3f));
  CHECK(!s.render.body);
  CHECK(!s.render.torso);
  CHECK(s.render.solver_tolerance == 1e-3);
  CHECK(s.render.warm_start_block == 3);
  CHECK(!s.render.video);
  CHECK(s.render.contact_sheet_columns == 4);
  CHECK(!s.render.antialias);
  CHECK(error_of({{"render", {{"antialias", 1}}}}) ==
        "scene.json: render.antialias: expected true or false, got 1");

  // "taper" is Faraj's pointy wisp; null turns the curvature clamp off.
  const wisp::io::Scene t = parse_scene(
      json::parse(R"({"style": {"profile": "taper", "curvature_clamp": null}})"), "scene.json");
  CHECK(t.style.geometry.profile.shape == wisp::vector::WidthProfile::Shape::Linear);
  CHECK(t.style.geometry.profile.at(1.0) == 0.0);
  CHECK(std::isinf(t.style.geometry.curvature_clamp));
}

TEST_CASE("the scene's body and projector options follow render.body and render.torso",
          "[io][scene]") {
  wisp::io::Scene s =
      parse_scene(json::parse(R"({"head": {"shoulder_radius": 0.05, "torso_turn": 0.2},
                                                  "light": {"direction": [1, 0, 0]}})"),
                  "scene.json");
  wisp::sim::BodyParams b = wisp::render::body_params(s);
  CHECK((b.head && b.neck && b.torso));
  CHECK(b.torso_turn == 0.2);
  // shoulder_radius scales the figure's depths (and the arms' thickness).
  const wisp::sim::BodyParams d =
      wisp::render::body_params(parse_scene(json::parse("{}"), "scene.json"));
  for (std::size_t i = 0; i < d.torso_shape.half_depth.size(); ++i)
    CHECK(b.torso_shape.half_depth[i] == Approx(d.torso_shape.half_depth[i] * 0.05 / 0.07));
  wisp::sim::ProjectorOptions o = wisp::render::projector_options(s);
  CHECK(o.light_dir == Eigen::Vector3d::UnitX());
  REQUIRE(o.body);
  CHECK(o.body->torso);
  s.render.torso = false;
  b = wisp::render::body_params(s);
  CHECK((b.head && !b.neck && !b.torso));
  CHECK(!wisp::render::projector_options(s).body);
  s.render.body = false;
  b = wisp::render::body_params(s);
  CHECK((!b.head && !b.neck && !b.torso));
}

TEST_CASE("bad style, light and render values name the field", "[io][scene]") {
  CHECK(error_of({{"style", {{"widht", 0.01}}}}) ==
        "scene.json: style.widht: unknown field (did you mean \"width\"?)");
  CHECK(error_of({{"style", {{"profile", "sin"}}}}) ==
        "scene.json: style.profile: expected one of taper, sine, got \"sin\" (did you mean "
        "\"sine\"?)");
  CHECK(error_of({{"style", {{"width", 0}}}}).find("scene.json: style.width: must be") == 0);
  CHECK(error_of({{"style", {{"curvature_clamp", -1}}}}).find("style.curvature_clamp") !=
        std::string::npos);
  CHECK(error_of({{"style", {{"hair_color", {1.5, 0, 0}}}}}) ==
        "scene.json: style.hair_color: colour components must be in [0, 1], got [1.5,0,0]");
  CHECK(error_of({{"style", {{"shadow_color", {0, 0}}}}})
            .find("style.shadow_color: expected an "
                  "array of 3 numbers") != std::string::npos);
  CHECK(error_of({{"style", {{"highlight_along", 2}}}}).find("style.highlight_along") !=
        std::string::npos);
  CHECK(error_of({{"style", {{"highlight_spread", 0}}}}).find("style.highlight_spread") !=
        std::string::npos);
  CHECK(error_of({{"style", {{"highlight_side", "up"}}}}).find("style.highlight_side") !=
        std::string::npos);
  CHECK(error_of({{"style", {{"highlight_along", 2}}}}).find("style.highlight_along") !=
        std::string::npos);
  CHECK(error_of({{"light", {{"direction", {0, 0, 0}}}}}) ==
        "scene.json: light.direction: must be a non-zero vector with components in [-1e6, 1e6]");
  CHECK(error_of({{"light", {{"directoin", {0, 0, 1}}}}}) ==
        "scene.json: light.directoin: unknown field (did you mean \"direction\"?)");
  CHECK(error_of({{"render", {{"video", 1}}}}) ==
        "scene.json: render.video: expected true or false, got 1");
  CHECK(error_of({{"render", {{"solver_tolerance", 0}}}}).find("render.solver_tolerance") !=
        std::string::npos);
  CHECK(error_of({{"render", {{"warm_start_block", 0}}}}).find("render.warm_start_block") !=
        std::string::npos);
  CHECK(
      error_of({{"render", {{"contact_sheet_columns", 0}}}}).find("render.contact_sheet_columns") !=
      std::string::npos);
  CHECK(error_of({{"render", {{"skin_colour", {1, 1, 1}}}}}) ==
        "scene.json: render.skin_colour: unknown field (did you mean \"skin_color\"?)");
  CHECK(error_of({{"sim", {{"preroll", -1}}}}).find("sim.preroll") != std::string::npos);
}
