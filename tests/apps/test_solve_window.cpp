// The colour solve covers only the curves' window (render_solve): the finished frames are those of
// a solve over the whole image, up to the solver's own error (a step of 1/255 in a few pixels),
// for a cold frame and for the warm-started frame after it, while the window holds well under the
// image's pixels (so the comparison covers a real cut).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "scene_fixture.hpp"

namespace render = wisp::render;
namespace diffusion = wisp::diffusion;
namespace sim = wisp::sim;

namespace {

const std::string kScene = WISP_SOURCE_DIR "/data/scenes/bob.json";
constexpr int kSize = 320;

render::FrameResult render_at(const render::SceneFrames& sf, int k, bool whole,
                              const render::FrameSolution* warm) {
  render::FrameSetup setup = render::frame_setup(sf.scene);
  setup.whole_image_solve = whole;
  return render::render_frame(sf.projected[k], render::frame_body(sf, k),
                              render::frame_occluders(sf, k), render::frame_base(sf, k), setup,
                              warm);
}

}  // namespace

TEST_CASE("solving the curves' window alone changes no pixel beyond the solver's error",
          "[render]") {
  const render::SceneFrames& sf = wisp::test::loaded_scene(kScene, kSize);
  const int k = wisp::test::five_angles(sf.anim)[2];
  const render::FrameResult cold_window = render_at(sf, k, false, nullptr);
  const render::FrameResult cold_whole = render_at(sf, k, true, nullptr);
  const render::FrameResult warm_window = render_at(sf, k + 1, false, &cold_window.solution);
  const render::FrameResult warm_whole = render_at(sf, k + 1, true, &cold_whole.solution);

  const diffusion::PixelWindow& w = cold_window.window;
  CHECK(w.pixel_count() < 0.8 * kSize * kSize);
  CHECK(cold_whole.window == diffusion::PixelWindow{0, 0, kSize, kSize});
  for (const auto* pair : {&cold_window, &warm_window}) {
    const render::FrameResult& a = *pair;
    const render::FrameResult& b = pair == &cold_window ? cold_whole : warm_whole;
    const std::vector<std::uint8_t> pa = render::rasterize_frame(a.picture),
                                    pb = render::rasterize_frame(b.picture);
    REQUIRE(pa.size() == pb.size());
    int differ = 0, largest = 0;
    for (size_t i = 0; i < pa.size(); ++i) {
      const int d = std::abs(int(pa[i]) - int(pb[i]));
      differ += d > 0;
      largest = std::max(largest, d);
    }
    INFO((pair == &cold_window ? "cold" : "warm") << " frame: " << differ << " bytes differ");
    CHECK(largest <= 1);
    CHECK(differ <= int(pa.size() / 1000));
    // The kept solution and the picture's hair image are the window's alone, and the hair is
    // black outside it: nothing was solved there.
    const diffusion::PixelWindow& v = a.window;
    CHECK(a.solution.window == v);
    CHECK(a.solution.colours.size() == 3 * v.pixel_count());
    CHECK(a.picture.hair_window == v);
    CHECK(a.picture.hair.width == v.width);
    CHECK(a.picture.hair.height == v.height);
    CHECK(a.picture.hair.planes.size() == 3 * v.pixel_count());
    std::vector<std::uint32_t> words(size_t(kSize) * kSize);
    render::pack_hair(a.picture, 0, 0, kSize, kSize, words.data(), kSize);
    int outside = 0, black = 0, inside_nonblack = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const std::uint32_t word = words[size_t(y) * kSize + x];
        if (x >= v.x && x < v.x + v.width && y >= v.y && y < v.y + v.height) {
          inside_nonblack += word != 0xff000000u;
          continue;
        }
        ++outside;
        black += word == 0xff000000u;
      }
    CHECK(outside > 0);
    CHECK(black == outside);
    CHECK(inside_nonblack > 0);
  }
}

TEST_CASE("a frame whose hair lies outside the picture solves nothing and shows no hair",
          "[render]") {
  const render::SceneFrames& sf = wisp::test::loaded_scene(kScene, kSize);
  const int k = wisp::test::five_angles(sf.anim)[2];
  sim::ProjectedFrame away = sf.projected[k];
  for (sim::ProjectedStrand& s : away.strands)
    for (Eigen::Vector2d& p : s.pixel) p.x() += 4 * kSize;  // far to the right
  const render::FrameSetup setup = render::frame_setup(sf.scene);
  const render::FrameResult r = render::render_frame(away, {}, {}, {}, setup, nullptr);
  CHECK(r.window.pixel_count() == 0);
  CHECK(r.solve.cycles == 0);
  // Nothing solved: the warm start for the next frame holds no colours (it stands for zeros).
  CHECK(r.solution.colours.empty());
  CHECK(r.picture.mask.polygons.empty());
  // The next frame, back in the picture, starts from that.
  const render::FrameResult next = render_at(sf, k, false, &r.solution);
  CHECK(next.window.pixel_count() > 0);
  CHECK(next.solve.converged);
}
