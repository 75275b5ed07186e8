// Hatching (vector/hatching.hpp) on data/scenes/hatch.json (the default scene in the `hatch`
// preset) at 320x320: the ink of the hatch strokes alone gets denser band by band as the hair
// gets darker; each stroke keeps its (along, across) place on its wisp from frame to frame while
// the hair moves (no shower door); strokes stay inside the region where their wisp shows; and
// `wisp render` draws them alike in the PNG and in the SVG's "hatching" group.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "image_checks.hpp"
#include "run_command.hpp"
#include "scene_fixture.hpp"
#include "vector/hatching.hpp"
#include "vector/ink_strokes.hpp"
#include "vector/polygon.hpp"
#include "vector/visible_region.hpp"
#include "vector/wisp_shader.hpp"

namespace render = wisp::render;
namespace vector = wisp::vector;
using Eigen::Vector2d;
using wisp::test::distance_to_rings;
using wisp::test::fresh_folder;
using wisp::test::run_command;

namespace {

const std::string kScene = WISP_SOURCE_DIR "/data/scenes/hatch.json";
constexpr int kSize = 320;

const render::SceneFrames& frames() {
  return wisp::test::loaded_scene(kScene, kSize);
}

// Frame k as `wisp render` draws it, with the arrangement's faces kept.
render::FrameResult render_k(int k) {
  const render::SceneFrames& sf = frames();
  render::FrameSetup setup = render::frame_setup(sf.scene);
  setup.keep_faces = true;
  return render::render_frame(sf.projected[k], render::frame_body(sf, k),
                              render::frame_occluders(sf, k), render::frame_base(sf, k), setup,
                              nullptr);
}

const wisp::sim::ProjectedStrand& strand_of(const wisp::sim::ProjectedFrame& f, int id) {
  for (const auto& s : f.strands)
    if (s.id == id) return s;
  throw std::runtime_error("no strand " + std::to_string(id));
}

// The ink of the hatch strokes alone, per pixel in [0, 1].
std::vector<double> hatch_ink(const render::FramePicture& pic) {
  render::FramePicture only;
  only.width = pic.width;
  only.height = pic.height;
  only.background = {1, 1, 1};
  only.ink = pic.hatching;
  for (render::InkStroke& s : only.ink) s.color = {0, 0, 0};
  const std::vector<std::uint8_t> rgba = render::rasterize_frame(only);
  std::vector<double> out(size_t(pic.width) * pic.height);
  for (size_t i = 0; i < out.size(); ++i) out[i] = 1 - rgba[4 * i + 1] / 255.0;
  return out;
}

// Distance from p to the boundary of the faces where wisp w is in front.
double distance_to_faces(const vector::ArrangementView& view, int w, const Vector2d& p) {
  double best = INFINITY;
  const auto ring = [&](const std::vector<Vector2d>& r) {
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const Vector2d a = r[j], d = r[i] - r[j];
      const double f = std::clamp((p - a).dot(d) / std::max(1e-12, d.squaredNorm()), 0.0, 1.0);
      best = std::min(best, (a + f * d - p).norm());
    }
  };
  for (const vector::ViewFace& f : view.faces) {
    if (f.front != w || f.outer.empty()) continue;
    ring(f.outer);
    for (const auto& h : f.holes) ring(h);
  }
  return best;
}

}  // namespace

TEST_CASE("hatch ink gets denser band by band as the hair gets darker", "[hatching]") {
  const render::SceneFrames& sf = frames();
  const vector::HairStyle& style = sf.scene.style;
  const int bands = int(style.hatching.tones.size());
  // Pixels by tone band (-1: lighter than every band), over three frames of the turn.
  std::vector<double> ink_sum(bands + 1, 0.0);
  std::vector<int> count(bands + 1, 0);
  for (int k : {0, 20, 40}) {
    const render::FrameResult r = render_k(k);
    REQUIRE(!r.hatching.empty());
    const std::vector<double> ink = hatch_ink(r.picture);
    const vector::VisibleRegions regions(r.arrangement.view, int(r.wisps.size()));
    const vector::FrameLight light = vector::frame_light(sf.projected[k], r.wisps, style);
    std::vector<char> seen(size_t(kSize) * kSize, 0);
    for (int w = 0; w < int(r.wisps.size()); ++w) {
      if (r.arrangement.visible[w].empty()) continue;
      const vector::WispChart chart(r.wisps[w], strand_of(sf.projected[k], r.wisps[w].strand),
                                    sf.projected[k].eye);
      const vector::WispShader shader(chart, style, light, nullptr);
      for (double t : chart.samples(0.5))
        for (double u = -0.8; u <= 0.8; u += 0.05) {
          const Vector2d p = chart.point(t, u);
          const int x = int(p.x()), y = int(p.y());
          if (x < 0 || y < 0 || x >= kSize || y >= kSize || seen[size_t(y) * kSize + x]) continue;
          // The whole pixel in the wisp's region, so its ink is this wisp's tone's.
          bool inside = true;
          for (double dx : {0.0, 1.0})
            for (double dy : {0.0, 1.0}) inside &= regions.contains(w, Vector2d(x + dx, y + dy));
          if (!inside) continue;
          seen[size_t(y) * kSize + x] = 1;
          const double xv = shader.x(t, u);
          int band = -1;
          while (band + 1 < bands && xv < style.hatching.tones[band + 1]) ++band;
          ink_sum[band + 1] += ink[size_t(y) * kSize + x];
          ++count[band + 1];
        }
    }
  }
  double prev = -1;
  for (int b = 0; b <= bands; ++b) {
    const double mean = ink_sum[b] / std::max(1, count[b]);
    INFO("band " << b - 1 << ": " << count[b] << " px, mean ink " << mean);
    CHECK(count[b] >= 200);
    CHECK(mean > prev);
    if (b > 0) CHECK(mean >= 0.6 * style.hatching.coverage[b - 1]);
    prev = mean;
  }
  // Lighter than every band: hardly any ink (strokes of band 0 just across its edge).
  CHECK(ink_sum[0] / std::max(1, count[0]) < 0.2 * ink_sum[1] / std::max(1, count[1]));
}

TEST_CASE("a hatch stroke keeps its (along, across) place on its wisp as the hair moves",
          "[hatching]") {
  const render::SceneFrames& sf = frames();
  // Frames 10 and 14: the head turns, the hair moves across the image.
  std::map<std::pair<int, int>, std::pair<Vector2d, Vector2d>> first;  // (strand, rank) -> from, to
  std::map<std::pair<int, int>, Vector2d> first_point;
  int same = 0, moved = 0;
  for (int k : {10, 14}) {
    const render::FrameResult r = render_k(k);
    REQUIRE(r.hatching.size() > 100);
    double worst = 0;
    for (const vector::HatchStroke& h : r.hatching) {
      // Its ends are where its wisp's chart puts its (along, across) coordinates this frame.
      const auto& strand = strand_of(sf.projected[k], h.strand);
      const vector::WispChart chart(r.wisps[h.wisp], strand, sf.projected[k].eye);
      const vector::HatchChart hc(r.wisps[h.wisp], chart, strand);
      const Vector2d a = h.from + h.f0 * (h.to - h.from), b = h.from + h.f1 * (h.to - h.from);
      const auto pa = hc.point(a.x(), a.y()), pb = hc.point(b.x(), b.y());
      REQUIRE(pa);
      REQUIRE(pb);
      worst = std::max({worst, (*pa - h.points.front()).norm(), (*pb - h.points.back()).norm()});
      const std::pair<int, int> key{h.strand, h.rank};
      const Vector2d mid = h.from + 0.5 * (h.to - h.from);
      const auto pm = hc.point(mid.x(), mid.y());
      if (k == 10) {
        first[key] = {h.from, h.to};
        if (pm) first_point[key] = *pm;
      } else if (first.count(key)) {
        CHECK(first[key].first == h.from);
        CHECK(first[key].second == h.to);
        ++same;
        if (pm && first_point.count(key)) moved += (*pm - first_point[key]).norm() > 2;
      }
    }
    INFO("frame " << k << ": stroke ends off their chart points by up to " << worst << " px");
    CHECK(worst < 0.06);  // the fit's tolerance
  }
  INFO(same << " strokes in both frames, " << moved << " of them moved more than 2 px");
  CHECK(same > 100);
  CHECK(moved > same / 2);
  // The list itself depends on the strand alone, not on the frame.
  const auto& s = sf.projected[0].strands.front();
  double len = 0;
  for (size_t i = 1; i < s.world.size(); ++i) len += (s.world[i] - s.world[i - 1]).norm();
  const auto a =
      vector::plan_wisp_strokes(s.id, len, sf.scene.style.geometry.width, sf.scene.style.hatching);
  const auto b = vector::plan_wisp_strokes(s.id, len + 0.01, sf.scene.style.geometry.width,
                                           sf.scene.style.hatching);
  REQUIRE(!a.empty());
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    if (a[i].from.x() + 0.5 < len)
      CHECK(std::find_if(b.begin(), b.end(), [&](const auto& q) {
              return q.from == a[i].from && q.to == a[i].to;
            }) != b.end());
}

TEST_CASE("hatch strokes never leave the region where their wisp shows", "[hatching]") {
  for (int k : {0, 30}) {
    const render::FrameResult r = render_k(k);
    const vector::VisibleRegions regions(r.arrangement.view, int(r.wisps.size()));
    int points = 0, outside = 0;
    double worst_width = 0;
    for (const vector::HatchStroke& h : r.hatching) {
      const int n = h.piece_count();
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < 16; ++j) {
          const double s = (i + j / 16.0) / n;
          const double width = vector::width_at(h.width, s);
          if (width < 0.05) continue;  // a tapered end: no ink
          ++points;
          const Vector2d p = wisp::diffusion::eval(h, s);
          // Outside by more than the fit's tolerance (the cuts are exact on the samples).
          if (!regions.contains(h.wisp, p) &&
              distance_to_faces(r.arrangement.view, h.wisp, p) > 0.06) {
            ++outside;
            worst_width = std::max(worst_width, width);
          }
        }
    }
    INFO("frame " << k << ": " << outside << " of " << points
                  << " stroke points outside their wisp's region, widest there " << worst_width
                  << " px");
    CHECK(points > 5000);
    CHECK(outside == 0);
  }
}

TEST_CASE("wisp render draws hatching alike in the PNG and the SVG", "[hatching][cli]") {
  const std::string dir = fresh_folder("hatching_svg");
  nlohmann::json scene;
  std::ifstream(kScene) >> scene;
  scene["render"] = {{"video", false}};
  std::ofstream(dir + "/scene.json") << scene.dump(2);
  const auto r =
      run_command(std::string(WISP_BIN_DIR) + "/wisp render " + dir + "/scene.json -o " + dir +
                  " --size 256x256 -q --anim " + wisp::test::simulated(kScene) + " --frames 0:1");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(dir + "/frame_0000.svg");
  const std::string svg((std::istreambuf_iterator<char>(in)), {});
  const size_t at = svg.find("<g id=\"hatching\"");
  REQUIRE(at != std::string::npos);
  // Above the hair, below the ink.
  CHECK(at > svg.find("id=\"hair\""));
  CHECK(at < svg.find("<g id=\"ink\""));
  // One id per stroke (hatching-hair-n, hatching-body-n), drawn as real strokes.
  int strokes = 0;
  for (size_t i = svg.find("id=\"hatching-"); i != std::string::npos;
       i = svg.find("id=\"hatching-", i + 1))
    ++strokes;
  CHECK(strokes > 200);
  CHECK(svg.find("stroke-width=", at) < svg.find("<g id=\"ink\""));
  REQUIRE(run_command("rsvg-convert " + dir + "/frame_0000.svg -o " + dir + "/svg.png").exit_code ==
          0);
  const cv::Mat png = cv::imread(dir + "/frame_0000.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat from_svg = cv::imread(dir + "/svg.png", cv::IMREAD_GRAYSCALE);
  REQUIRE(png.size() == from_svg.size());
  // Ink pixels (hatching and outlines) at least half covered, in both. Not exactly the same: the
  // PNG fills each stroke's exact width once, viewers stroke the SVG's constant-width pieces one
  // by one, compositing their round caps twice where they meet (a 0.7 px stroke's pixels are
  // mostly partly covered, so a darker threshold would count mostly that difference).
  const cv::Mat a = png < 128, b = from_svg < 128;
  const double iou = wisp::test::mask_iou(a, b);
  INFO("dark pixels: PNG " << cv::countNonZero(a) << ", SVG " << cv::countNonZero(b) << ", IoU "
                           << iou);
  CHECK(cv::countNonZero(a) > 1000);
  CHECK(iou >= 0.9);
  CHECK(std::abs(cv::mean(255 - png)[0] - cv::mean(255 - from_svg)[0]) <
        0.05 * cv::mean(255 - png)[0]);
}

TEST_CASE("hatch lines on the body stay on the skin where it shows", "[hatching]") {
  const render::SceneFrames& sf = frames();
  for (int k : {0, 30}) {
    const render::FrameResult r = render_k(k);
    const render::BodyLayer body = render::frame_body(sf, k);
    REQUIRE(r.body_hatching.size() > 20);
    std::vector<std::vector<Vector2d>> hair;  // the mask's rings, even-odd
    for (const vector::MaskPolygon& m : r.arrangement.mask.polygons) {
      hair.push_back(m.outer);
      hair.insert(hair.end(), m.holes.begin(), m.holes.end());
    }
    std::map<int, std::vector<Vector2d>> by_surface;
    int points = 0, on_hair = 0;
    for (const render::BodyHatch& h : r.body_hatching) {
      const auto& c = h.stroke.curve;
      const int n = c.piece_count();
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < 8; ++j) {
          const double s = (i + j / 8.0) / n;
          if (vector::width_at(h.stroke.curve_width, s) < 0.05) continue;
          const Vector2d p = wisp::diffusion::eval(c, s);
          ++points;
          bool in = false;
          for (const auto& ring : hair) in ^= vector::inside_polygon(ring, p);
          if (in && distance_to_rings(hair, p) > 0.06) ++on_hair;
          by_surface[h.surface].push_back(p);
        }
    }
    // Off the surface's visible part by more than the fit's tolerance: neither the point nor
    // any of 16 points 0.06 px around it shows the surface.
    int off_skin = 0;
    for (const auto& [s, pts] : by_surface) {
      const std::vector<bool> shows = render::body_surface_shows(body.projected, s, pts);
      for (size_t i = 0; i < pts.size(); ++i) {
        if (shows[i]) continue;
        std::vector<Vector2d> around;
        for (int a = 0; a < 16; ++a)
          around.push_back(pts[i] +
                           0.06 * Vector2d(std::cos(a * M_PI / 8), std::sin(a * M_PI / 8)));
        const std::vector<bool> near = render::body_surface_shows(body.projected, s, around);
        off_skin += std::none_of(near.begin(), near.end(), [](bool b) { return b; });
      }
    }
    INFO("frame " << k << ": " << points << " points of " << r.body_hatching.size()
                  << " body lines; " << on_hair << " on the hair, " << off_skin
                  << " off their surface's visible part");
    CHECK(points > 1000);
    CHECK(on_hair == 0);
    CHECK(off_skin == 0);
  }
}
