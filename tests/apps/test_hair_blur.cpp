// Blur along the hair (vector/hair_blur.hpp): depth of field, soft tips and motion measured on
// rendered frames of hand-made strands. Edge widths are the 10-90 % rise of the hair against the
// background across a wisp's side; a Gaussian of sigma s widens a sharp edge by 2.563 s.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "apps/render/picture.hpp"
#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "run_command.hpp"
#include "tests/vector/scenes.hpp"
#include "vector/hair_blur.hpp"

namespace render = wisp::render;
namespace vector = wisp::vector;
namespace sim = wisp::sim;
using Eigen::Vector2d;

namespace {

constexpr int kW = 320, kH = 256;
constexpr double kFocus = 2;  // the focus plane of every lens below

// One flat colour for the whole hair, a white background, no base: a wisp's side is a clean
// step from white to the hair's grey, whatever blurs it.
render::FrameSetup flat_setup() {
  render::FrameSetup s;
  s.style.hair = s.style.shadow = s.style.highlight = Eigen::Vector3f(0.2f, 0.2f, 0.2f);
  s.style.base.enabled = false;
  s.style.geometry.profile = vector::WidthProfile::constant();
  s.style.geometry.width = 0.12;
  s.background = {1, 1, 1};
  s.lens.focus_distance = kFocus;
  return s;
}

// A vertical strand through column x from y = 10 (root) to 246 (tip) at depth z.
sim::ProjectedStrand vertical(int id, double x, double z) {
  return wisp::test::straight(id, {x, 10}, {x, 246}, z, z, 9);
}

struct Frame {
  render::FrameResult result;
  std::vector<std::uint8_t> rgba;
};

Frame render_one(const sim::ProjectedFrame& f, const render::FrameSetup& setup,
                 const sim::ProjectedFrame* neighbour = nullptr) {
  Frame out;
  out.result = render::render_frame(f, {}, {}, {}, setup, nullptr, neighbour);
  out.rgba = render::rasterize_frame(out.result.picture);
  return out;
}

// Coverage of the hair in [0,1] from the green channel (255 background, 51 hair).
double coverage(const Frame& f, int x, int y) {
  return (255.0 - f.rgba[(size_t(y) * kW + x) * 4 + 1]) / (255.0 - 51.0);
}

// The 10-90 % width of the left side of the wisp around column xc, along row y.
double edge_width(const Frame& f, double xc, int y) {
  std::vector<double> v;
  const int x0 = int(xc) - 60;
  for (int x = x0; x <= int(xc); ++x) v.push_back(coverage(f, x, y));
  const auto crossing = [&](double level) {
    for (size_t i = 1; i < v.size(); ++i)
      if (v[i - 1] < level && v[i] >= level)
        return x0 + double(i - 1) + (level - v[i - 1]) / (v[i] - v[i - 1]);
    FAIL("the profile never reaches " << level);
    return 0.0;
  };
  return crossing(0.9) - crossing(0.1);
}

}  // namespace

TEST_CASE("the circle of confusion of a thin lens", "[blur]") {
  const vector::Lens lens{2.0, 0.06};
  CHECK(vector::circle_of_confusion_px(lens, 800, 2.0) == 0);
  CHECK(vector::circle_of_confusion_px(lens, 800, 3.0) == Approx(800 * 0.06 / 6));
  CHECK(vector::circle_of_confusion_px(lens, 800, 1.5) == Approx(800 * 0.06 / 6));
  CHECK(!vector::blurs({}, {}));
  CHECK(vector::blurs({}, lens));
}

TEST_CASE(
    "depth of field: a wisp in focus stays sharp, one behind it softens with the circle of "
    "confusion",
    "[blur]") {
  // Wisp A on the focus plane, wisp B at depth 3 in the middle column; apertures give B a circle
  // of confusion of 0 to 16 px.
  const sim::ProjectedFrame f =
      wisp::test::frame_of({vertical(0, 60, kFocus), vertical(1, 180, 3)}, kW, kH);
  render::FrameSetup setup = flat_setup();
  const Frame sharp = render_one(f, setup);
  CHECK(sharp.result.picture.blur.empty());
  const double sharp_a = edge_width(sharp, 60, 128), sharp_b = edge_width(sharp, 180, 128);
  CHECK(sharp_a < 1.5);
  CHECK(sharp_b < 1.5);

  double previous = sharp_b;
  for (const double c : {4.0, 8.0, 12.0, 16.0}) {
    setup.lens.aperture = c / (800 * (1 / kFocus - 1 / 3.0));
    REQUIRE(vector::circle_of_confusion_px(setup.lens, 800, 3) == Approx(c));
    const Frame blurred = render_one(f, setup);
    REQUIRE(!blurred.result.picture.blur.empty());
    const double a = edge_width(blurred, 60, 128), b = edge_width(blurred, 180, 128);
    INFO("circle of confusion " << c << " px: edge widths in focus " << a << ", behind " << b);
    CHECK(std::abs(a - sharp_a) < 0.1);  // in focus: as sharp as without a lens
    CHECK(b > previous + 0.5);           // grows with the circle of confusion
    // sigma c/4 widens the edge by 2.563 c / 4, added in quadrature to the sharp edge's width.
    const double widening = std::sqrt(b * b - sharp_b * sharp_b);
    CHECK(widening == Approx(2.563 * c / 4).epsilon(0.25));
    previous = b;
  }
  CHECK(previous > 5 * sharp_a);
}

TEST_CASE("the blurred hair is not cut by the hard mask, and its matte softens with it", "[blur]") {
  const sim::ProjectedFrame f = wisp::test::frame_of({vertical(0, 160, 3)}, kW, kH);
  render::FrameSetup setup = flat_setup();
  setup.lens.aperture = 0.12;  // a 16 px circle of confusion
  const Frame blurred = render_one(f, setup);
  const render::FramePicture& pic = blurred.result.picture;
  const std::vector<std::uint8_t> hard = render::rasterize_mask(pic.mask, kW, kH);
  const std::vector<std::uint8_t> matte = render::hair_matte(pic);
  int beyond = 0, softer = 0;
  for (int x = 0; x < kW; ++x) {
    const size_t i = size_t(128) * kW + x;
    if (hard[i] == 0 && coverage(blurred, x, 128) > 0.05) ++beyond;
    if (hard[i] == 255 && matte[i] < 240) ++softer;
    CHECK(std::abs(matte[i] / 255.0 - coverage(blurred, x, 128)) < 0.02);
  }
  CHECK(beyond >= 4);  // the blurred hair reaches past the sharp silhouette
  CHECK(softer >= 4);  // and fades inside it
}

TEST_CASE("soft tips soften the tips only", "[blur]") {
  const sim::ProjectedFrame f = wisp::test::frame_of({vertical(0, 160, 2)}, kW, kH);
  render::FrameSetup setup = flat_setup();
  setup.style.geometry.profile = vector::WidthProfile::faraj_taper();
  setup.style.geometry.width = 0.1;
  const Frame sharp = render_one(f, setup);
  setup.style.blur.tip = 8;  // sigma 4 px at the tip of this 256 px high frame
  setup.style.blur.tip_fade = 0.3;
  const Frame soft = render_one(f, setup);
  REQUIRE(!soft.result.picture.blur.empty());
  // Rows by strand parameter: y = 10 + 236 u.
  const auto row_difference = [&](double u0, double u1) {
    int most = 0;
    for (int y = int(10 + 236 * u0); y < int(10 + 236 * u1); ++y)
      for (int x = 0; x < kW; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t i = (size_t(y) * kW + x) * 4 + c;
          most = std::max(most, std::abs(int(sharp.rgba[i]) - int(soft.rgba[i])));
        }
    return most;
  };
  CHECK(row_difference(0.0, 0.6) <= 2);   // root and middle: as sharp as before
  CHECK(row_difference(0.9, 1.0) >= 40);  // the tip: visibly softer
  CHECK(edge_width(soft, 160, int(10 + 236 * 0.4)) ==
        Approx(edge_width(sharp, 160, int(10 + 236 * 0.4))).margin(0.05));
}

TEST_CASE("motion softens a moving wisp by the smear of its shutter", "[blur]") {
  const sim::ProjectedFrame f = wisp::test::frame_of({vertical(0, 160, 3)}, kW, kH);
  const sim::ProjectedFrame before = wisp::test::frame_of({vertical(0, 140, 3)}, kW, kH);
  render::FrameSetup setup = flat_setup();
  const Frame sharp = render_one(f, setup);
  setup.style.blur.shutter = 0.5;  // 20 px per frame: a 10 px smear, sigma 10 / sqrt(12)
  const Frame moving = render_one(f, setup, &before);
  REQUIRE(!moving.result.picture.blur.empty());
  const double s = edge_width(sharp, 160, 128), m = edge_width(moving, 160, 128);
  CHECK(std::sqrt(m * m - s * s) == Approx(2.563 * 10 / std::sqrt(12.0)).epsilon(0.25));

  // The same frame with no motion (or no neighbour) is the sharp frame, byte for byte.
  const Frame still = render_one(f, setup, &f);
  CHECK(still.result.picture.blur.empty());
  CHECK(still.rgba == sharp.rgba);
  CHECK(render_one(f, setup).rgba == sharp.rgba);
}

TEST_CASE("with blur off, or nothing that blurs, frames and SVGs are unchanged", "[blur]") {
  const sim::ProjectedFrame f =
      wisp::test::frame_of({vertical(0, 100, kFocus), vertical(1, 200, 3)}, kW, kH);
  render::FrameSetup setup;  // the default style: Faraj's colours, with ink
  setup.style.ink.silhouette_width = 2;
  const Frame plain = render_one(f, setup);
  const auto same = [&](const Frame& other) {
    CHECK(other.result.picture.blur.empty());
    CHECK(other.rgba == plain.rgba);
    for (const render::SvgStyle style : {render::SvgStyle::Embedded, render::SvgStyle::Flat})
      CHECK(render::format_frame_svg(other.result.picture, style) ==
            render::format_frame_svg(plain.result.picture, style));
  };
  setup.lens.focus_distance = kFocus;  // a focus plane, but a pinhole
  same(render_one(f, setup));
  setup.style.blur.shutter = 1;  // a shutter, but nothing moves
  same(render_one(f, setup, &f));
  setup.style.blur.max = 8;
  setup.style.blur.tip_fade = 0.5;  // fields of sources that are off
  same(render_one(f, setup));
}

TEST_CASE("blurred SVGs: the embedded image carries the softened matte, flat layers Gaussians",
          "[blur]") {
  const sim::ProjectedFrame f = wisp::test::frame_of({vertical(0, 160, 3)}, kW, kH);
  render::FrameSetup setup = flat_setup();
  setup.lens.aperture = 0.12;
  setup.style.ink.silhouette_width = 2;
  setup.flat_regions = true;
  const render::FramePicture pic = render_one(f, setup).result.picture;
  const std::string embedded = render::format_frame_svg(pic, render::SvgStyle::Embedded);
  CHECK(embedded.find("<image id=\"hair-shading\"") != std::string::npos);
  CHECK(embedded.find("clip-path=\"url(#hair-silhouette)\"") == std::string::npos);
  CHECK(embedded.find("<feGaussianBlur stdDeviation=\"4\"/>") != std::string::npos);
  // The ink along the silhouette: sigma 4 is half-octave level 6 (0.5 px * 2^3).
  const size_t ink = embedded.find("<g id=\"ink\"");
  REQUIRE(ink != std::string::npos);
  CHECK(embedded.find("<g filter=\"url(#blur6)\">", ink) != std::string::npos);
  const std::string flat = render::format_frame_svg(pic, render::SvgStyle::Flat);
  const size_t hair = flat.find("<g id=\"hair\"");
  REQUIRE(hair != std::string::npos);
  CHECK(flat.find("<g filter=\"url(#blur6)\">", hair) != std::string::npos);
}

TEST_CASE("the depth-of-field scene blurs the hair behind the face, its lens read from the camera",
          "[blur]") {
  const std::string scene = WISP_SOURCE_DIR "/data/scenes/depth-of-field.json";
  render::SceneFramesOptions o;
  o.anim = wisp::test::simulated(scene);
  o.width = o.height = 160;
  const render::SceneFrames frames = render::load_scene_frames(scene, o);
  const render::FrameSetup setup = render::frame_setup(frames.scene);
  CHECK(setup.lens.aperture == 0.06);
  CHECK(setup.lens.focus_distance == 1.0);
  const int k = 30;
  const render::FrameResult r = render::render_frame(
      frames.projected[k], render::frame_body(frames, k), render::frame_occluders(frames, k),
      render::frame_base(frames, k), setup, nullptr, render::motion_neighbour(frames, k));
  REQUIRE(r.picture.blur.size() == size_t(160 * 160));
  REQUIRE(r.picture.blurred_hair.size() == size_t(4 * 160 * 160));
  CHECK(*std::max_element(r.picture.blur.begin(), r.picture.blur.end()) > 1);
  CHECK(r.solution.blur == r.picture.blur);  // the next frame's warm start
}
