// The saved animation (.wsim): bit-exact round trip, determinism of `simulate` + write, and
// rejection of truncated, corrupt and foreign files.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/anim_file.hpp"
#include "sim/simulate.hpp"
#include "tests/test_folder.hpp"

using namespace wisp;
using Eigen::Vector3d;

namespace {

std::filesystem::path temp_dir() {
  return wisp::test::test_folder("anim_file");
}

std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

sim::SimSetup small_setup() {
  sim::HairParams hair;
  hair.count = 12;
  hair.segments = 10;
  sim::MotionParams motion;
  motion.preset = sim::MotionPreset::Nod;
  motion.duration = 1.0;
  sim::SimParams params;
  params.wind.velocity = Vector3d(0.3, 0, 0);
  params.wind.gust = 0.5;
  return sim::make_setup(sim::HeadParams{}, hair, motion, params);
}

}  // namespace

TEST_CASE("a saved animation reads back bit for bit", "[io][anim]") {
  const auto path = temp_dir() / "a.wsim";
  sim::Animation anim = sim::simulate(small_setup());
  anim.head.shape = sim::HeadKind::Mesh;  // exercise the mesh section too
  anim.head.mesh.vertices = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  anim.head.mesh.triangles = {Eigen::Vector3i(0, 1, 2)};
  io::write_animation(path, anim);
  const sim::Animation back = io::read_animation(path);
  CHECK(back.fps == anim.fps);
  CHECK(back.head.shape == sim::HeadKind::Mesh);
  CHECK(back.head.mesh.vertices == anim.head.mesh.vertices);
  CHECK(back.head.mesh.triangles == anim.head.mesh.triangles);
  REQUIRE(back.frames.size() == anim.frames.size());
  bool same = true;
  for (std::size_t f = 0; f < anim.frames.size(); ++f) {
    same = same && back.frames[f].frame == anim.frames[f].frame &&
           back.frames[f].time == anim.frames[f].time &&
           back.frames[f].head.position == anim.frames[f].head.position &&
           back.frames[f].head.rotation.coeffs() == anim.frames[f].head.rotation.coeffs() &&
           back.frames[f].strands == anim.frames[f].strands;
  }
  CHECK(same);
}

TEST_CASE("two runs of the same scene write byte-identical files", "[io][anim]") {
  const auto dir = temp_dir();
  io::write_animation(dir / "1.wsim", sim::simulate(small_setup()));
  io::write_animation(dir / "2.wsim", sim::simulate(small_setup()));
  const std::string a = bytes_of(dir / "1.wsim"), b = bytes_of(dir / "2.wsim");
  CHECK(a.size() > 1000);
  CHECK(a == b);
}

TEST_CASE("truncated, corrupt and foreign .wsim files are clear errors", "[io][anim]") {
  const auto dir = temp_dir();
  io::write_animation(dir / "ok.wsim", sim::simulate(small_setup()));
  const std::string bytes = bytes_of(dir / "ok.wsim");
  const auto write = [&](const char* name, const std::string& data) {
    std::ofstream(dir / name, std::ios::binary) << data;
    return dir / name;
  };
  CHECK_THROWS_WITH(io::read_animation(write("cut.wsim", bytes.substr(0, bytes.size() / 2))),
                    Catch::Contains("cut.wsim") && Catch::Contains("truncated"));
  CHECK_THROWS_WITH(io::read_animation(write("tiny.wsim", bytes.substr(0, 30))),
                    Catch::Contains("truncated"));
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  CHECK_THROWS_WITH(io::read_animation(write("flip.wsim", flipped)),
                    Catch::Contains("checksum mismatch"));
  std::string version = bytes;
  version[4] = 7;
  CHECK_THROWS_WITH(io::read_animation(write("v7.wsim", version)), Catch::Contains("version 7"));
  CHECK_THROWS_WITH(io::read_animation(write("png.wsim", "\x89PNG....")),
                    Catch::Contains("not a .wsim"));
  CHECK_THROWS_WITH(io::read_animation(dir / "none.wsim"), Catch::Contains("cannot open"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("clump widths are saved with the animation and read back", "[io][anim][clumps]") {
  const auto dir = temp_dir();
  sim::Animation anim = sim::simulate(small_setup());
  for (const sim::Polyline& s : anim.frames.front().strands) {
    anim.widths.emplace_back();
    for (std::size_t i = 0; i < s.size(); ++i) anim.widths.back().push_back(0.01 + 0.001 * i);
  }
  io::write_animation(dir / "w.wsim", anim);
  const sim::Animation back = io::read_animation(dir / "w.wsim");
  CHECK(back.widths == anim.widths);
  CHECK(back.frames.back().strands == anim.frames.back().strands);
  // Without widths the file is the version-1 layout of before, flags 0.
  io::write_animation(dir / "plain.wsim", sim::simulate(small_setup()));
  CHECK(io::read_animation(dir / "plain.wsim").widths.empty());
  CHECK(bytes_of(dir / "plain.wsim")[8] == 0);
  CHECK(bytes_of(dir / "plain.wsim").size() + 8 * 12 * 11 == bytes_of(dir / "w.wsim").size());
  // A width list that does not match the strands is refused; so are unknown flags.
  anim.widths.back().pop_back();
  CHECK_THROWS_WITH(io::write_animation(dir / "bad.wsim", anim), Catch::Contains("strand 11"));
  std::string flags = bytes_of(dir / "plain.wsim");
  flags[8] = 6;
  std::ofstream(dir / "flags.wsim", std::ios::binary) << flags;
  CHECK_THROWS_WITH(io::read_animation(dir / "flags.wsim"),
                    Catch::Contains("unknown .wsim flags 6"));
  std::filesystem::remove_all(dir);
}
