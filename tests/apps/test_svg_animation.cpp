// animation.svg from frames' SVGs (apps/render/svg_animation.hpp) on small made-up pictures: a
// layer that never changes is written once and never animated, runs of equal frames share one
// group, content repeated in groups apart is defined once and used, the first frame is the one
// displayed without animation, and the timing covers the loop at the frame rate.
#include <catch2/catch.hpp>
#include <regex>
#include <string>
#include <vector>

#include "apps/render/picture.hpp"
#include "apps/render/svg_animation.hpp"

using namespace wisp::render;

namespace {

// A 64 x 48 picture: a body square at `body_x`, and an ink stroke at `ink_y`.
FramePicture picture(double body_x, double ink_y) {
  FramePicture pic;
  pic.width = 64;
  pic.height = 48;
  BodyPath body;
  body.color = Rgb(0.9f, 0.7f, 0.6f);
  const Eigen::Vector2d a(body_x + 0.371, 10.259), b(body_x + 20.113, 10.417),
      c(body_x + 20.781, 30.093), d(body_x + 0.557, 30.311);
  body.loops.push_back({a, a, b, b, b, c, c, c, d, d, d, a, a});
  pic.body.push_back(body);
  InkStroke ink;
  ink.kind = "silhouette";
  ink.curve.points = {{5, ink_y}, {20, ink_y}, {40, ink_y}, {60, ink_y}};
  ink.curve_width = {{0, 2}, {1, 2}};
  ink.points = {{5, ink_y}, {60, ink_y}};
  ink.width = {2, 2};
  pic.ink.push_back(ink);
  return pic;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// The opening tag of the element with this id.
std::string tag(const std::string& text, const std::string& id) {
  const std::size_t p = text.find(" id=\"" + id + "\"");
  REQUIRE(p != std::string::npos);
  const std::size_t start = text.rfind('<', p);
  return text.substr(start, text.find('>', p) - start + 1);
}

}  // namespace

TEST_CASE("animation.svg writes what does not change once and shows each run of frames in turn",
          "[svg]") {
  // Body: at 4, 4, 30, 4 (frames 0, 1 equal; 3 repeats them). Ink: moves every frame.
  const std::vector<double> body_x = {4, 4, 30, 4}, ink_y = {40, 41, 42, 43};
  std::vector<std::string> frames;
  for (std::size_t k = 0; k < body_x.size(); ++k)
    frames.push_back(format_frame_svg(picture(body_x[k], ink_y[k]), SvgStyle::Flat));
  SvgAnimationStats stats;
  const std::string svg = animate_svg_frames(frames, {}, 8, &stats);
  INFO(svg);
  CHECK(stats.frames == 4);
  CHECK(stats.bytes == svg.size());

  // The background never changes: one group, no animation, displayed.
  CHECK(tag(svg, "background-f0").find("display") == std::string::npos);
  CHECK(count(svg, "<g id=\"background-f") == 1);
  CHECK(count(svg, "id=\"background-fill") == 1);
  // The body: frames 0-1 one group, then frame 2, then frame 3; frame 3's square is frame 0's,
  // defined once and used from both groups.
  CHECK(count(svg, "<g id=\"body-f") == 3);
  CHECK(tag(svg, "body-f0").find("display") == std::string::npos);
  CHECK(tag(svg, "body-f2").find("display=\"none\"") != std::string::npos);
  CHECK(count(svg, "<path id=\"head-1-f0-shared\"") == 1);
  CHECK(count(svg, "<use id=\"head-1-f0\" xlink:href=\"#head-1-f0-shared\"") == 1);
  CHECK(count(svg, "<use id=\"head-1-f3\" xlink:href=\"#head-1-f0-shared\"") == 1);
  CHECK(count(svg, "id=\"head-1-f2\"") == 1);  // not shared: only frame 2 has it
  // The ink: a group per frame, each shown for its eighth of a second in a 0.5 s loop.
  CHECK(count(svg, "<g id=\"ink-f") == 4);
  const std::regex timing(
      "<g id=\"ink-f2\" display=\"none\"><animate sodipodi:type=\"\" "
      "attributeName=\"display\" values=\"none;inline;none\" "
      "keyTimes=\"0;0.5;0.75\" dur=\"0.5s\" calcMode=\"discrete\" "
      "repeatCount=\"indefinite\"/>");
  CHECK(std::regex_search(svg, timing));
  CHECK(svg.find("values=\"none;inline\" keyTimes=\"0;0.75\"") != std::string::npos);  // ink-f3
  CHECK(svg.find("values=\"inline;none\" keyTimes=\"0;0.25\"") != std::string::npos);  // ink-f0
  CHECK(count(svg, "id=\"ink-silhouette-1-f") == 4);
}

TEST_CASE("animation.svg refuses frames that are not wisp frame SVGs, naming them", "[svg]") {
  const std::string good = format_frame_svg(picture(4, 40), SvgStyle::Embedded);
  const auto fails = [&](const std::string& bad, const std::string& message) {
    try {
      animate_svg_frames({good, bad}, {"a.svg", "b.svg"}, 24);
      FAIL("accepted");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()).find("b.svg: " + message) == 0);
    }
  };
  fails("<svg", "not XML");
  fails("<html/>", "not an SVG frame");
  fails("<svg width=\"64\" height=\"48\"/>", "not a wisp frame SVG");
  FramePicture other = picture(4, 40);
  other.width = 65;
  fails(format_frame_svg(other, SvgStyle::Embedded), "the frame is 65x48");
}
