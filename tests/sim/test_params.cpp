// The scene's physical parameters: every closed choice has a name that reads back as itself, every
// struct's validate() names the field, and the simulator's entry points refuse what validate()
// refuses, with the part in front.
#include <catch2/catch.hpp>

#include <cmath>
#include <initializer_list>
#include <set>
#include <string>

#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/hair_model.hpp"
#include "sim/motion.hpp"
#include "sim/simulate.hpp"
#include "sim_fixtures.hpp"

using namespace wisp::sim;

namespace {

// Every value of E (listed by the caller) has one table entry, and its name parses back to it.
template <class E>
void check_names(std::initializer_list<E> all) {
  CHECK(choices(E{}).size() == all.size());
  std::set<std::string> names;
  for (const E value : all) {
    const std::string name = choice_name(value);
    INFO(name);
    CHECK(!name.empty());
    CHECK(parse_choice<E>(name) == value);
    names.insert(name);
  }
  CHECK(names.size() == all.size());
  CHECK(!parse_choice<E>("no such name"));
  CHECK(!parse_choice<E>(""));
}

// The message of validate(params), or "" when it passes.
template <class Params>
std::string invalid(const Params& params) {
  try {
    validate(params);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("every choice's name parses back to it", "[sim][params]") {
  check_names({HeadKind::Ellipsoid, HeadKind::Mesh});
  check_names({HairSource::Procedural, HairSource::Json, HairSource::Hair});
  check_names({HairCurl::Straight, HairCurl::Wavy, HairCurl::Curly});
  check_names({MotionPreset::None, MotionPreset::Turn, MotionPreset::Nod, MotionPreset::Shake,
               MotionPreset::Walk, MotionPreset::Keys});
  check_names({SimModel::Dftl, SimModel::Featherstone, SimModel::Rope});
  // The names scene files use.
  CHECK(std::string(choice_name(SimModel::Featherstone)) == "featherstone");
  CHECK(parse_choice<HairSource>("hair") == HairSource::Hair);
  CHECK(choice_names<MotionPreset>() ==
        std::vector<std::string>{"none", "turn", "nod", "shake", "walk", "keys"});
}

TEST_CASE("defaults are valid and validate() names the first bad field", "[sim][params]") {
  CHECK(invalid(HeadParams{}).empty());
  CHECK(invalid(HairParams{}).empty());
  CHECK(invalid(MotionParams{}).empty());
  CHECK(invalid(SimParams{}).empty());
  CHECK(invalid(CameraParams{}).empty());

  HeadParams head;
  head.shape = HeadKind::Mesh;
  CHECK(invalid(head) == "mesh: shape \"mesh\" needs an OBJ file name");
  HairParams hair;
  hair.count = 0;
  CHECK(invalid(hair).empty());  // no hair: a head that only grows fur
  hair.count = -1;
  CHECK(invalid(hair) == "count: must be >= 0 (0 = no hair), got -1");
  hair.count = 0;
  hair.source = HairSource::Json;
  CHECK(invalid(hair) == "file: source \"json\" needs a strand file name");
  hair.file = "strands.json";
  CHECK(invalid(hair).empty());  // a file keeps all its strands with count 0
  hair.length = std::nan("");
  CHECK(invalid(hair) == "length: must be in (0, 10] m");
  MotionParams motion;
  motion.preset = MotionPreset::Keys;
  CHECK(invalid(motion) == "keys: preset \"keys\" needs at least one keyframe");
  motion.keys = {Keyframe{1, {}, {}}, Keyframe{1, {}, {}}};
  CHECK(invalid(motion) == "keys[1].time: keyframe times must increase");
  SimParams sim;
  sim.step_rate = 10;
  CHECK(invalid(sim) == "step_rate: must be in [sim.fps, 100000] Hz");
  sim = SimParams{};
  sim.wind.gust = -1;
  CHECK(invalid(sim) == "wind.gust: must be in [0, 1000] m/s");
  CameraParams camera;
  camera.up = camera.target - camera.eye;
  CHECK(invalid(camera) == "up: must not be parallel to the view");
  BodyParams body;
  body.torso_turn = 2;
  CHECK(invalid(body) == "torso_turn: must be in [0, 1]");
}

TEST_CASE("the simulator refuses what validate() refuses, naming the part", "[sim][params]") {
  SimSetup setup = test::single_strand(0.3, 4, 0, 1.0);
  setup.sim.substeps = 0;
  const std::string why = invalid(setup.sim);
  REQUIRE(!why.empty());
  CHECK_THROWS_WITH(simulate(setup), "sim." + why);

  HairParams hair;
  hair.segments = 1001;
  CHECK_THROWS_WITH(make_setup(HeadParams{}, hair, MotionParams{}, SimParams{}),
                    "hair." + invalid(hair));
  MotionParams motion;
  motion.speed = 0;
  CHECK_THROWS_WITH(make_base_setup(HeadParams{}, motion, SimParams{}),
                    "motion." + invalid(motion));
  HeadParams head;
  head.shoulder_radius = -1;
  CHECK_THROWS_WITH(make_base_setup(head, MotionParams{}, SimParams{}), "head." + invalid(head));
  CameraParams camera;
  camera.fov_deg = 180;
  CHECK_THROWS_WITH(Camera::look_at(camera), "camera." + invalid(camera));
  BodyParams body;
  body.slices = 2;
  CHECK_THROWS_WITH(BodyModel(HeadGeometry{}, body), "body." + invalid(body));
}
