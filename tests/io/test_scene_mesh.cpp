// The OBJ reader for head meshes, and a mesh head used by the simulation.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "apps/render/scene_setup.hpp"
#include "io/scene.hpp"
#include "io/scene_mesh.hpp"
#include "sim/head.hpp"
#include "tests/test_folder.hpp"

namespace {

std::filesystem::path temp_dir() {
  return wisp::test::test_folder("scene_mesh");
}

// A closed cube of side 0.2 centred on the origin: quads, v/vt/vn face items, a negative index.
const char* kCube = R"(# cube
v -0.1 -0.1 -0.1
v 0.1 -0.1 -0.1
v 0.1 0.1 -0.1
v -0.1 0.1 -0.1
v -0.1 -0.1 0.1
v 0.1 -0.1 0.1
v 0.1 0.1 0.1
v -0.1 0.1 0.1
vn 0 0 1
f 1 4 3 2
f 5/1/1 6/1/1 7/1/1 8/1/1
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 -3
)";

}  // namespace

TEST_CASE("OBJ faces are fanned into triangles with resolved indices", "[io][obj]") {
  const auto path = temp_dir() / "cube.obj";
  std::ofstream(path) << kCube;
  const wisp::sim::TriangleMesh m = wisp::io::read_obj(path);
  CHECK(m.vertices.size() == 8);
  REQUIRE(m.triangles.size() == 12);
  CHECK(m.triangles[2] == Eigen::Vector3i(4, 5, 6));
  CHECK(m.triangles[11] == Eigen::Vector3i(1, 6, 5));  // -3 is the 6th vertex
  // Closed, so it is a valid head: the centre is inside, a corner-ward point outside.
  wisp::sim::HeadGeometry g;
  g.shape = wisp::sim::HeadKind::Mesh;
  g.mesh = m;
  const wisp::sim::HeadShape head(g);
  CHECK(head.distance(Eigen::Vector3d::Zero()) == Approx(-0.1).margin(0.01));
  CHECK(head.distance(Eigen::Vector3d(0.15, 0, 0)) == Approx(0.05).margin(0.01));
}

TEST_CASE("malformed OBJ files are errors naming the file and line", "[io][obj]") {
  const auto dir = temp_dir();
  std::ofstream(dir / "bad_index.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  CHECK_THROWS_WITH(wisp::io::read_obj(dir / "bad_index.obj"),
                    Catch::Contains("bad_index.obj:4") && Catch::Contains("refers to no vertex"));
  std::ofstream(dir / "bad_vertex.obj") << "v 0 zero 0\n";
  CHECK_THROWS_WITH(wisp::io::read_obj(dir / "bad_vertex.obj"),
                    Catch::Contains("bad_vertex.obj:1"));
  std::ofstream(dir / "empty.obj") << "# nothing\n";
  CHECK_THROWS_WITH(wisp::io::read_obj(dir / "empty.obj"), Catch::Contains("no faces"));
  CHECK_THROWS_WITH(wisp::io::read_obj(dir / "missing.obj"), Catch::Contains("cannot open"));
}

TEST_CASE("a scene with a mesh head and shoulders simulates", "[io][obj]") {
  const auto dir = temp_dir();
  std::ofstream(dir / "cube.obj") << kCube;
  std::ofstream(dir / "scene.json") << R"({
    "head": {"shape": "mesh", "mesh": "cube.obj", "mesh_scale": 0.8, "shoulders": true},
    "hair": {"count": 10, "segments": 12, "length": 0.4},
    "motion": {"preset": "nod", "duration": 1.0}})";
  const wisp::io::Scene scene = wisp::io::load_scene(dir / "scene.json");
  const wisp::sim::SimSetup setup = wisp::render::load_sim_setup(scene);
  REQUIRE(setup.rest.size() == 10);
  REQUIRE(setup.body);
  const wisp::sim::BodyShape body(*setup.body);
  const wisp::sim::Animation anim = wisp::sim::simulate(setup);
  const wisp::sim::HeadShape head(setup.head);
  for (const auto& f : anim.frames)
    for (const auto& s : f.strands)
      for (std::size_t i = 1; i < s.size(); ++i) {
        CHECK(head.distance(f.head.to_local(s[i])) > 0);
        CHECK(body.distance(f.head, s[i]) > 0);
      }
  std::filesystem::remove_all(dir);
}
