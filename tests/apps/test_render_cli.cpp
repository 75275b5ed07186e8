// `wisp render` end to end on the default scene at 256x256: every output valid, PNG and SVG
// agree, hair where the strands are and in the style's colours, deterministic, resumable,
// coherent over time, and bad input refused cleanly.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "image_checks.hpp"
#include "io/anim_file.hpp"
#include "io/scene.hpp"
#include "io/video_file.hpp"
#include "run_command.hpp"
#include "sim/camera.hpp"

using wisp::test::fresh_folder;
using wisp::test::run_command;
namespace fs = std::filesystem;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";
const std::string kScene = WISP_SOURCE_DIR "/data/scenes/default.json";

std::string frame(const std::string& dir, int k, const char* prefix = "frame_",
                  const char* ext = "png") {
  char buf[64];
  std::snprintf(buf, sizeof buf, "/%s%04d.%s", prefix, k, ext);
  return dir + buf;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

const std::string& animation() {
  return wisp::test::simulated(kScene);
}

std::string render(const std::string& dir, const std::string& extra = "") {
  const auto r = run_command(kWisp + " render " + kScene + " -o " + dir +
                             " --size 256x256 --anim " + animation() + " -q " + extra);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return dir;
}

}  // namespace

TEST_CASE("wisp render writes valid PNG, SVG, video, contact sheet and stats", "[cli][render]") {
  const std::string dir = render(fresh_folder("render_outputs"), "--frames 0:6 --masks");
  const wisp::io::Scene scene = wisp::io::load_scene(kScene);
  const wisp::sim::Animation anim = wisp::io::read_animation(animation());
  wisp::io::Scene small = scene;
  small.camera.width = small.camera.height = 256;
  wisp::sim::Projector projector(anim.head, small.camera);

  for (int k = 0; k < 6; ++k) {
    INFO("frame " << k);
    const cv::Mat png = cv::imread(frame(dir, k), cv::IMREAD_COLOR);
    REQUIRE(png.cols == 256);
    REQUIRE(png.rows == 256);
    const cv::Mat mask = cv::imread(frame(dir, k, "mask_"), cv::IMREAD_GRAYSCALE);
    REQUIRE(mask.cols == 256);
    CHECK(cv::countNonZero(mask > 127) > 2000);  // there is hair

    // The SVG parses and rasterises as a whole, and its hair layer (shown alone: the background
    // and body layers hidden) covers the region of the PNG's hair mask.
    const std::string svg = frame(dir, k, "frame_", "svg");
    REQUIRE(run_command("rsvg-convert " + svg + " -o " + dir + "/svg_all.png").exit_code == 0);
    CHECK(cv::imread(dir + "/svg_all.png").cols == 256);
    std::string text = read_file(svg);
    for (const std::string id : {"<g id=\"background\"", "<g id=\"body\""})
      text.replace(text.find(id), id.size(), id + " style=\"display:none\"");
    std::ofstream(dir + "/hair_only.svg") << text;
    const std::string svg_hair = dir + "/svg_hair.png";
    const auto r = run_command("rsvg-convert " + dir + "/hair_only.svg -o " + svg_hair);
    REQUIRE(r.exit_code == 0);
    cv::Mat svg_rgba = cv::imread(svg_hair, cv::IMREAD_UNCHANGED);
    REQUIRE(svg_rgba.channels() == 4);
    cv::Mat svg_alpha;
    cv::extractChannel(svg_rgba, svg_alpha, 3);
    CHECK(wisp::test::mask_iou(svg_alpha > 127, mask > 127) >= 0.98);

    // Hair lies inside the hull of the projected strands (grown by the widest wisp).
    const wisp::sim::ProjectedFrame pf = projector.project(anim.frames[k]);
    std::vector<cv::Point2f> samples;
    double widest = 0;
    for (const auto& s : pf.strands)
      for (size_t i = 0; i < s.pixel.size(); ++i) {
        samples.emplace_back(float(s.pixel[i].x()), float(s.pixel[i].y()));
        widest = std::max(widest, 0.5 * scene.style.geometry.width * pf.focal_px / s.depth[i]);
      }
    std::vector<cv::Point> hull;
    std::vector<cv::Point2f> hullf;
    cv::convexHull(samples, hullf);
    for (const auto& p : hullf) hull.emplace_back(int(std::lround(p.x)), int(std::lround(p.y)));
    cv::Mat inside = cv::Mat::zeros(256, 256, CV_8U);
    cv::fillConvexPoly(inside, hull, 255);
    cv::dilate(inside, inside,
               cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                         cv::Size(int(2 * widest) + 3, int(2 * widest) + 3)));
    cv::Mat outside_hull;
    cv::bitwise_and(mask > 0, ~inside, outside_hull);
    CHECK(cv::countNonZero(outside_hull) == 0);

    // Fully covered hair pixels show colours within the range of the style's colours.
    const auto& st = scene.style;
    for (int c = 0; c < 3; ++c) {
      const float lo = std::min({st.hair[c], st.shadow[c], st.highlight[c]});
      const float hi = std::max({st.hair[c], st.shadow[c], st.highlight[c]});
      double vmin, vmax;
      std::vector<cv::Mat> ch;
      cv::split(png, ch);
      cv::minMaxLoc(ch[2 - c], &vmin, &vmax, nullptr, nullptr, mask == 255);
      CHECK(vmin >= lo * 255 - 1);
      CHECK(vmax <= hi * 255 + 1);
    }
  }
  CHECK(wisp::io::count_video_frames(dir + "/preview.mp4") == 6);
  CHECK(cv::imread(dir + "/contact.png").cols > 256);
  std::ifstream in(dir + "/stats.json");
  const auto stats = nlohmann::json::parse(in);
  CHECK(stats["frames"].size() == 6);
  CHECK(stats["frames"][0]["wisps"].get<int>() > 50);
  CHECK(stats["frames"][0]["solver_converged"] == true);
  CHECK(stats["stage_ms_median"]["solve"].get<double>() > 0);
}

namespace {

// How two images differ, in words: how many pixels, by how much, where; empty when they are equal.
std::string pixel_difference(const cv::Mat& x, const cv::Mat& y) {
  if (x.size() != y.size() || x.type() != y.type()) return "sizes differ";
  cv::Mat diff, any;
  cv::absdiff(x, y, diff);
  cv::reduce(diff.reshape(1, int(diff.total())), any, 1, cv::REDUCE_MAX);  // a row per pixel
  any = any.reshape(1, x.rows);
  const int count = cv::countNonZero(any > 0);
  if (count == 0) return "";
  double most = 0;
  cv::minMaxLoc(diff.reshape(1), nullptr, &most);
  const cv::Rect box = cv::boundingRect(any > 0);
  return std::to_string(count) + " pixels differ, by up to " + std::to_string(int(most)) +
         ", in x " + std::to_string(box.x) + ".." + std::to_string(box.x + box.width - 1) + ", y " +
         std::to_string(box.y) + ".." + std::to_string(box.y + box.height - 1);
}

// The images an SVG embeds (base64 data URIs), decoded, and the text without them.
std::pair<std::vector<cv::Mat>, std::string> embedded_images(const std::string& svg) {
  static const std::string kDigits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<cv::Mat> images;
  std::string text;
  size_t at = 0;
  for (size_t b; (b = svg.find("base64,", at)) != std::string::npos;) {
    const size_t e = svg.find('"', b);
    text += svg.substr(at, b - at);
    std::vector<std::uint8_t> bytes;
    std::uint32_t bits = 0;
    int count = 0;
    for (size_t i = b + 7; i < e && svg[i] != '='; ++i) {
      bits = bits << 6 | std::uint32_t(kDigits.find(svg[i]));
      if ((count += 6) >= 8) bytes.push_back(std::uint8_t(bits >> (count -= 8)));
    }
    images.push_back(cv::imdecode(bytes, cv::IMREAD_UNCHANGED));
    at = e;
  }
  return {images, text + svg.substr(at)};
}

// What differs between two renders' frame k, in words. `pixels`: the SVG's text (the geometry),
// the pixels of the hair image it embeds, the solver's record, the PNG's pixels. `bytes`: a PNG
// (the frame, or the SVG's image) whose pixels are the same in other compressed bytes. The
// ground rules forbid both; they are told apart because they have different causes (a byte-only
// difference was igzip's stray hash slot, which depended on the stack's address: png_encode.cpp,
// deflate_rows; docs/render.md).
struct FrameDifference {
  std::string pixels, bytes;
};
FrameDifference frame_difference(const std::string& x, const std::string& y, int k) {
  FrameDifference out;
  const std::string svg_x = read_file(frame(x, k, "frame_", "svg"));
  const std::string svg_y = read_file(frame(y, k, "frame_", "svg"));
  if (svg_x != svg_y) {
    const auto [images_x, text_x] = embedded_images(svg_x);
    const auto [images_y, text_y] = embedded_images(svg_y);
    if (text_x != text_y || images_x.size() != images_y.size()) out.pixels += "SVG text differs; ";
    for (size_t i = 0; i < std::min(images_x.size(), images_y.size()); ++i) {
      const std::string d = pixel_difference(images_x[i], images_y[i]);
      (d.empty() ? out.bytes : out.pixels) +=
          "SVG image " + std::to_string(i) + ": " + (d.empty() ? "other bytes" : d) + "; ";
    }
  }
  const auto record = [&](const std::string& dir) {
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
    const nlohmann::json& f = stats["frames"][k];
    return f["wisps"].dump() + " wisps, " + f["solver_cycles"].dump() + " cycles, residual " +
           f["solver_residual"].dump();
  };
  const std::string record_x = record(x), record_y = record(y);
  if (record_x != record_y) out.pixels += "solver records " + record_x + " vs " + record_y + "; ";
  if (read_file(frame(x, k)) != read_file(frame(y, k))) {
    const std::string d = pixel_difference(cv::imread(frame(x, k)), cv::imread(frame(y, k)));
    (d.empty() ? out.bytes : out.pixels) += "PNG: " + (d.empty() ? "other bytes" : d);
  }
  return out;
}

// Frames 0 .. count-1 of two renders are the same files (PNG and SVG), byte for byte.
void same_frames(const std::string& x, const std::string& y, int count) {
  for (int k = 0; k < count; ++k) {
    INFO("frame " << k);
    const FrameDifference d = frame_difference(x, y, k);
    CHECK(d.pixels == "");
    CHECK(d.bytes == "");
  }
}

}  // namespace

TEST_CASE("wisp render is deterministic, with 1 or 2 threads", "[cli][render]") {
  const std::string a = render(fresh_folder("render_det_a"), "--frames 0:4 --threads 1");
  const std::string b = render(fresh_folder("render_det_b"), "--frames 0:4 --threads 2");
  const std::string c = render(fresh_folder("render_det_c"), "--frames 0:4 --threads 2");
  same_frames(a, b, 4);
  same_frames(b, c, 4);
}

TEST_CASE("a killed render resumes to the same files as an uninterrupted one", "[cli][render]") {
  const std::string whole = render(fresh_folder("render_whole"), "--frames 0:12");
  // Interrupted after frame 4: frames 0-4 exist, frame 5 was being written (a stale temporary).
  const std::string part = render(fresh_folder("render_part"), "--frames 0:5");
  std::ofstream(part + "/.frame_0005.partial-999999.png") << "half a frame";
  render(part, "--frames 0:12");
  CHECK(!fs::exists(part + "/.frame_0005.partial-999999.png"));
  // The resumed run's stats.json still holds every frame's record, those of the first run too.
  std::ifstream in(part + "/stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  CHECK(stats["rendered"] == 7);
  CHECK(stats["skipped"] == 5);
  REQUIRE(stats["frames"].size() == 12);
  for (int k = 0; k < 12; ++k) {
    CHECK(stats["frames"][k]["frame"] == k);
    // The solver's setup is part of the solve's time.
    const nlohmann::json& ms = stats["frames"][k]["ms"];
    CHECK(ms["solve_setup"].get<double>() > 0);
    CHECK(ms["solve_setup"].get<double>() <= ms["solve"].get<double>());
  }
  same_frames(whole, part, 12);
  // A later run skips what exists; --force renders again, to the same file.
  const std::string before = read_file(frame(part, 3));
  const auto r = run_command(kWisp + " render " + kScene + " -o " + part +
                             " --size 256x256 --anim " + animation() + " --frames 0:12 --force -q");
  CHECK(r.exit_code == 0);
  CHECK((read_file(frame(part, 3)) == before));  // (not decomposed: Catch would print the PNG)
}

TEST_CASE("hair does not pop between frames of a slow turn", "[cli][render]") {
  const std::string dir = render(fresh_folder("render_coherence"), "--frames 0:24 --masks");
  std::vector<double> change;
  cv::Mat prev;
  for (int k = 0; k < 24; ++k) {
    cv::Mat img = cv::imread(frame(dir, k), cv::IMREAD_COLOR),
            mask = cv::imread(frame(dir, k, "mask_"), cv::IMREAD_GRAYSCALE);
    img.convertTo(img, CV_32FC3);
    if (!prev.empty()) {
      cv::Mat diff;
      cv::absdiff(img, prev, diff);
      cv::Mat hair = mask > 0;
      change.push_back(cv::mean(diff, hair)[0] + cv::mean(diff, hair)[1] + cv::mean(diff, hair)[2]);
    }
    prev = img;
  }
  std::vector<double> sorted = change;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  for (size_t i = 0; i < change.size(); ++i) {
    INFO("frames " << i << " -> " << i + 1 << ": " << change[i] << " (median " << median << ")");
    CHECK(change[i] <= 3 * median);
  }
}

TEST_CASE("wisp render refuses bad input with one line and exit code 2", "[cli][render]") {
  const std::string dir = fresh_folder("render_bad");
  std::ofstream(dir + "/bad.json") << R"({"hair": {"count": -3}})";
  const struct {
    std::string args, expected;
  } cases[] = {
      {dir + "/bad.json -o " + dir + "/out", "hair.count"},
      {kScene + " -o /proc/wisp-out --anim " + animation(), "/proc/wisp-out"},
      {kScene + " -o " + dir + "/out --anim " + animation() + " --frames 90:120", "has 97 frames"},
      {kScene + " -o " + dir + "/out --frames 5:2", "greater than"},
      {kScene + " -o " + dir + "/out --size 0x9", "between 1 and 16384"},
      // Refused by the encoder's probe, which runs beside the first frame: awaited before that
      // frame is written.
      {kScene + " -o " + dir + "/out --anim " + animation() + " --size 1x1 --frames 0:1",
       "--size 1x1: " + dir + "/out/preview.mp4: cannot encode a 1x1 video"},
  };
  for (const auto& c : cases) {
    INFO(c.args);
    const auto r = run_command(kWisp + " render " + c.args + " -q");
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains(c.expected));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK(!fs::exists(dir + "/out"));  // bad input writes nothing, not even the folder
  }
}
