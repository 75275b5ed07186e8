// Start-up: each command loads the shared libraries it uses and no others (docs/performance.md,
// "Start-up"). The dynamic loader itself reports what it maps (LD_DEBUG=files, on stderr), for
// the dispatcher `wisp` and the wisp-<command> it runs alike.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "run_command.hpp"

using wisp::test::fresh_folder;
using wisp::test::run_command;

namespace {

const std::string kBin = WISP_BIN_DIR;

// The libraries the loader mapped while running `command` ("libpng16.so.16"...), and its output.
std::set<std::string> loaded_libraries(const std::string& command, std::string* output) {
  const auto r = run_command("LD_DEBUG=files " + command);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::set<std::string> libraries;
  const std::regex file(R"(file=(\S+) \[)");
  for (std::sregex_iterator it(r.output.begin(), r.output.end(), file), end; it != end; ++it)
    libraries.insert(std::filesystem::path((*it)[1].str()).filename().string());
  *output = r.output;
  return libraries;
}

// The first of `libraries` whose name contains one of `names`, or "".
std::string any_of(const std::set<std::string>& libraries,
                   std::initializer_list<const char*> names) {
  for (const std::string& l : libraries)
    for (const char* n : names)
      if (l.find(n) != std::string::npos) return l;
  return "";
}

// The libraries `wisp diffuse` maps for data/drawings/<name>.xml at 48x48, and its output.
std::set<std::string> diffuse_libraries(const std::string& name, std::string* output) {
  const std::string out = fresh_folder("startup_" + name);
  const auto libraries =
      loaded_libraries(kBin + "/wisp diffuse " WISP_SOURCE_DIR "/data/drawings/" + name +
                           ".xml -o " + out + "/" + name + ".png --size 48x48",
                       output);
  CHECK(std::filesystem::exists(out + "/" + name + ".png"));
  return libraries;
}

}  // namespace

TEST_CASE("wisp diffuse loads neither video, Bullet, Cairo nor CGAL's number libraries",
          "[cli][startup]") {
  std::string output;
  const auto libraries = diffuse_libraries("circle", &output);
  INFO(output);
  // The report covers the command that did the work (wisp-diffuse, which the dispatcher runs under
  // its own name): its PNG writer's deflate (ISA-L) was loaded.
  REQUIRE(libraries.count("libisal.so.2") == 1);
  CHECK(any_of(libraries, {"videoio", "imgcodecs", "avcodec", "gst", "wisp-video"}) == "");
  CHECK(any_of(libraries, {"Bullet", "LinearMath"}) == "");
  CHECK(any_of(libraries, {"cairo", "libgmp", "libmpfr"}) == "");
  // 24 on Debian 12 (OpenCV's core brings X11, GL dispatch and LAPACK); 250 before the split.
  CHECK(libraries.size() <= 30);
  // circle.xml is blurred: the blur module brought OpenCV.
  CHECK(libraries.count("wisp-blur.so") == 1);
}

TEST_CASE("wisp diffuse loads OpenCV only for a drawing with blur", "[cli][startup]") {
  std::string output;
  const auto sharp = diffuse_libraries("crossing", &output);
  INFO(output);
  REQUIRE(sharp.count("libisal.so.2") == 1);  // the command ran
  CHECK(any_of(sharp, {"opencv", "wisp-blur", "libX11", "lapack"}) == "");
  CHECK(sharp.size() <= 12);  // 11 on Debian 12
  const auto help = loaded_libraries(kBin + "/wisp diffuse --help", &output);
  CHECK(any_of(help, {"opencv", "wisp-blur"}) == "");
}

TEST_CASE("a blurred drawing without the blur module is refused with one line naming it",
          "[cli][startup]") {
  // The command executable alone, without lib/wisp/ beside its bin/ folder.
  const std::string root = fresh_folder("startup_no_blur");
  std::filesystem::create_directories(root + "/bin");
  std::filesystem::copy_file(kBin + "/wisp-diffuse", root + "/bin/wisp-diffuse");
  const std::string png = root + "/circle.png";
  const auto blurred = run_command(
      root + "/bin/wisp-diffuse diffuse " WISP_SOURCE_DIR "/data/drawings/circle.xml -o " + png +
      " --size 48x48");
  INFO(blurred.output);
  CHECK(blurred.exit_code != 0);
  CHECK(blurred.output.find("wisp-blur.so") != std::string::npos);
  CHECK(blurred.output.find("build or install wisp whole") != std::string::npos);
  CHECK(std::count(blurred.output.begin(), blurred.output.end(), '\n') == 1);
  CHECK(!std::filesystem::exists(png));
  // A sharp drawing needs no module.
  CHECK(run_command(root +
                    "/bin/wisp-diffuse diffuse " WISP_SOURCE_DIR "/data/drawings/crossing.xml -o " +
                    png + " --size 48x48")
            .exit_code == 0);
}

TEST_CASE("wisp --help and wisp render --help load no stage library, video only when written",
          "[cli][startup]") {
  std::string output;
  const auto top = loaded_libraries(kBin + "/wisp --help", &output);
  CHECK(any_of(top, {"opencv", "Bullet", "tbb", "png", "cairo"}) == "");
  CHECK(top.size() <= 6);  // libstdc++, libm, libgcc_s, libc, and the loader's own
  const auto render = loaded_libraries(kBin + "/wisp render --help", &output);
  CHECK(any_of(render, {"Bullet"}) != "");  // the render command's own libraries: it ran
  CHECK(any_of(render, {"videoio", "imgcodecs", "avcodec", "wisp-video"}) == "");
}

TEST_CASE("wisp render --no-previews writes no video and loads no video module", "[cli][startup]") {
  const std::string scene = WISP_SOURCE_DIR "/data/scenes/default.json";
  const std::string out = fresh_folder("startup_render");
  std::string output;
  const auto libraries = loaded_libraries(
      kBin + "/wisp render " + scene + " -o " + out +
          " --size 48x48 --frames 0:1 -q --no-previews --anim " + wisp::test::simulated(scene),
      &output);
  INFO(output);
  CHECK(std::filesystem::exists(out + "/frame_0000.png"));
  CHECK(any_of(libraries, {"videoio", "avcodec", "wisp-video"}) == "");
}

TEST_CASE("wisp names the command executable it cannot find", "[cli][startup]") {
  // The dispatcher alone, without the wisp-<command> executables beside it.
  const std::string bin = fresh_folder("startup_alone");
  std::filesystem::copy_file(kBin + "/wisp", bin + "/wisp");
  const auto r = run_command(bin + "/wisp diffuse x.xml -o x.png");
  CHECK(r.exit_code == 2);
  CHECK(r.output == "wisp: error: cannot run the diffuse command (" + bin +
                        "/wisp-diffuse: No such file or directory); build or install wisp whole\n");
  // Help and errors of the top level need no command executable.
  CHECK(run_command(bin + "/wisp --help").exit_code == 0);
}
