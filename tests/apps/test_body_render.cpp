// The body layer of `wisp render` end to end, at 256x256: the skin is flat and seamless (inside
// each tone region, 2 px from any outline, every pixel has exactly the tone's colour, in the PNG
// and in the SVG rasterised by rsvg-convert: no interior edge is drawn), and the face is its own
// group, drawn on the body and under the hair.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apps/render/scene_frames.hpp"
#include "diffusion/bezier.hpp"
#include "run_command.hpp"

using Eigen::Vector2d;
using wisp::test::fresh_folder;
using wisp::test::run_command;

namespace {

const std::string kScene = WISP_SOURCE_DIR "/data/scenes/default.json";

std::string frame_file(const std::string& dir, const char* prefix, int k, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "/%s%04d.%s", prefix, k, ext);
  return dir + buf;
}

// Where closed cubic loops cover pixel centres under the nonzero rule (scanlines over the loops
// flattened finely).
cv::Mat coverage(const std::vector<std::vector<Vector2d>>& loops, int w, int h) {
  std::vector<std::pair<Vector2d, Vector2d>> edges;
  for (const auto& q : loops)
    for (std::size_t i = 0; i + 3 < q.size(); i += 3) {
      const wisp::diffusion::Cubic c{q[i], q[i + 1], q[i + 2], q[i + 3]};
      Vector2d a = q[i];
      for (int k = 1; k <= 32; ++k) {
        const Vector2d b = wisp::diffusion::eval(c, k / 32.0);
        edges.emplace_back(a, b);
        a = b;
      }
    }
  cv::Mat out = cv::Mat::zeros(h, w, CV_8U);
  for (int y = 0; y < h; ++y) {
    const double yc = y + 0.5;
    std::vector<std::pair<double, int>> cross;
    for (const auto& [a, b] : edges) {
      if ((a.y() <= yc) == (b.y() <= yc)) continue;
      cross.emplace_back(a.x() + (yc - a.y()) / (b.y() - a.y()) * (b.x() - a.x()),
                         b.y() > a.y() ? 1 : -1);
    }
    std::sort(cross.begin(), cross.end());
    int winding = 0;
    for (std::size_t i = 0; i + 1 < cross.size(); ++i) {
      winding += cross[i].second;
      if (winding == 0) continue;
      for (int x = std::max(0, int(std::ceil(cross[i].first - 0.5)));
           x < w && x + 0.5 < cross[i + 1].first; ++x)
        out.at<std::uint8_t>(y, x) = 255;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("inside each flat skin tone the body's pixels are exactly the tone, in PNG and SVG",
          "[cli][render][body]") {
  const std::string anim = wisp::test::simulated(kScene);
  const std::string dir = fresh_folder("body_tones");
  wisp::render::SceneFramesOptions options;
  options.anim = anim;
  options.width = options.height = 256;
  const wisp::render::SceneFrames frames = wisp::render::load_scene_frames(kScene, options);
  const wisp::render::BodyTones tones = wisp::render::body_tones(frames.scene);
  // The tones as each writer turns them into bytes: Cairo for the PNG, hex in the SVG.
  wisp::render::FramePicture probe;
  probe.width = probe.height = 1;
  wisp::render::BodyPath all;
  all.loops = {{{-1, -1},
                {-1, 2},
                {-1, 2},
                {2, 2},
                {2, 2},
                {2, 2},
                {2, -1},
                {2, -1},
                {2, -1},
                {-1, -1},
                {-1, -1},
                {-1, -1},
                {-1, -1}}};
  cv::Vec3b png_tone[2], svg_tone[2];
  for (int t = 0; t < 2; ++t) {
    all.color = t == 0 ? tones.lit : tones.shadow;
    probe.body = {all};
    const std::vector<std::uint8_t> px = wisp::render::rasterize_frame(probe);
    png_tone[t] = cv::Vec3b(px[2], px[1], px[0]);
    for (int c = 0; c < 3; ++c)
      svg_tone[t][2 - c] = std::uint8_t(std::lround(std::clamp(all.color[c], 0.0f, 1.0f) * 255));
  }

  for (int k : {0, 28, 60}) {
    INFO("frame " << k);
    const auto r = run_command(std::string(WISP_BIN_DIR "/wisp render ") + kScene + " -o " + dir +
                               " --size 256x256 -q --masks --anim " + anim + " --frames " +
                               std::to_string(k) + ":" + std::to_string(k + 1));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const std::string svg = frame_file(dir, "frame_", k, "svg");
    REQUIRE(run_command("rsvg-convert " + svg + " -o " + dir + "/svg.png").exit_code == 0);
    const cv::Mat png = cv::imread(frame_file(dir, "frame_", k, "png"), cv::IMREAD_COLOR);
    const cv::Mat from_svg = cv::imread(dir + "/svg.png", cv::IMREAD_COLOR);
    const cv::Mat hair = cv::imread(frame_file(dir, "mask_", k, "png"), cv::IMREAD_GRAYSCALE);
    REQUIRE(png.size() == cv::Size(256, 256));
    REQUIRE(from_svg.size() == png.size());

    // The painter's result per pixel centre, from the picture model: 0 none, 1 lit, 2 shadow.
    const wisp::render::BodyLayer body = wisp::render::frame_body(frames, k);
    // One path per tone per surface: a lit fill and a shadow region for each of the five.
    REQUIRE(body.paths.size() >= 8);
    REQUIRE(body.paths.size() <= 10);
    cv::Mat tone = cv::Mat::zeros(256, 256, CV_8U);
    for (const wisp::render::BodyPath& p : body.paths)
      tone.setTo(p.shadow ? 2 : 1, coverage(p.loops, 256, 256));
    // Away from every outline (the tone regions' and those hidden under later surfaces, where
    // a thinner-than-a-pixel sliver may show) and from what lies over the skin: the hair (its
    // anti-aliased mask) and the face's strokes.
    cv::Mat near = hair > 0;
    const auto draw = [&](const std::vector<Vector2d>& q, double width) {
      for (std::size_t i = 0; i + 3 < q.size(); i += 3) {
        const wisp::diffusion::Cubic c{q[i], q[i + 1], q[i + 2], q[i + 3]};
        for (int j = 0; j < 16; ++j) {
          const Vector2d a = wisp::diffusion::eval(c, j / 16.0),
                         b = wisp::diffusion::eval(c, (j + 1) / 16.0);
          cv::line(near, cv::Point(int(std::floor(a.x())), int(std::floor(a.y()))),
                   cv::Point(int(std::floor(b.x())), int(std::floor(b.y()))), 255,
                   int(std::ceil(width)));
        }
      }
    };
    for (const wisp::render::BodyPath& p : body.paths)
      for (const auto& loop : p.loops) draw(loop, 1);
    for (const wisp::render::InkStroke& s : body.face) {
      double widest = 0;
      for (const auto& [at, w] : s.curve_width) widest = std::max(widest, w);
      draw(s.curve.points, widest + 1);
    }
    const cv::Mat disk = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5));
    cv::dilate(near, near, disk);  // 2 px

    for (int t = 1; t <= 2; ++t) {
      const cv::Mat inside = (tone == t) & ~near;
      int checked = 0, png_off = 0, svg_off = 0, worst = 0;
      for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
          if (!inside.at<std::uint8_t>(y, x)) continue;
          ++checked;
          const cv::Vec3b a = png.at<cv::Vec3b>(y, x), b = from_svg.at<cv::Vec3b>(y, x);
          png_off += a != png_tone[t - 1];
          svg_off += b != svg_tone[t - 1];
          for (int c = 0; c < 3; ++c)
            worst = std::max(
                {worst, std::abs(a[c] - png_tone[t - 1][c]), std::abs(b[c] - svg_tone[t - 1][c])});
        }
      std::printf(
          "[measured] frame %d, %s tone: %d pixels 2 px inside, %d off in the PNG, %d in the SVG "
          "(worst by %d)\n",
          k, t == 1 ? "lit" : "shadow", checked, png_off, svg_off, worst);
      CHECK(checked > (t == 1 ? 3000 : 150));  // most of the body, not just slivers
      CHECK(png_off == 0);
      CHECK(svg_off == 0);
    }
  }
}

TEST_CASE("the face is drawn on the body, under the hair, as its own SVG group",
          "[cli][render][body]") {
  const std::string anim = wisp::test::simulated(kScene);
  const std::string dir = fresh_folder("body_face");
  const auto r = run_command(std::string(WISP_BIN_DIR "/wisp render ") + kScene + " -o " + dir +
                             " --size 256x256 -q --anim " + anim + " --frames 28:29");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(frame_file(dir, "frame_", 28, "svg"));
  const std::string svg((std::istreambuf_iterator<char>(in)), {});
  const std::size_t body = svg.find("<g id=\"body\""), face = svg.find("<g id=\"face\""),
                    hair = svg.find("<image id=\"hair-shading\""), ink = svg.find("<g id=\"ink\"");
  REQUIRE(face != std::string::npos);
  CHECK(body < face);
  CHECK(face < hair);
  CHECK(hair < ink);
  // Facing the camera (frame 28 ends the turn towards it), the face shows its strokes.
  std::size_t strokes = 0;
  for (std::size_t p = svg.find("id=\"face-"); p != std::string::npos;
       p = svg.find("id=\"face-", p + 1))
    ++strokes;
  CHECK(strokes >= 9);
}
