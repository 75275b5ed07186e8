// wisp-inspect end to end on frame 10 of the default scene at 256x256: each --snapshot layer
// shows what it means (faces and coverage against the dumped face polygons rasterized here, the
// mask and the image against `wisp render`'s own files), --dump agrees with the renderer's
// statistics, bad input is refused with exit code 2, and under Xvfb the window opens, toggles a
// layer on a key press (xdotool) and answers a click.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "apps/inspect/layers.hpp"
#include "run_command.hpp"

using nlohmann::json;
using wisp::test::fresh_folder;
using wisp::test::run_command;
namespace fs = std::filesystem;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";
const std::string kInspect = WISP_BIN_DIR "/wisp-inspect";
const std::string kScene = WISP_SOURCE_DIR "/data/scenes/default.json";
constexpr int kSize = 256, kFrame = 10;

const std::string& folder() {
  static const std::string dir = fresh_folder("inspect");
  return dir;
}

std::string frame_args(int frame = kFrame) {
  return kScene + " --anim " + wisp::test::simulated(kScene) + " --size " + std::to_string(kSize) +
         "x" + std::to_string(kSize) + " --frame " + std::to_string(frame);
}

// The snapshot of `layers` (comma-separated), as written by wisp-inspect.
cv::Mat snapshot(const std::string& layers, const std::string& extra = "") {
  std::string file = layers;
  for (char& c : file)
    if (c == ',') c = '_';
  if (!extra.empty()) file += "_" + std::to_string(std::hash<std::string>{}(extra));
  const std::string path = folder() + "/" + file + ".png";
  const auto r = run_command(kInspect + " " + frame_args() + " --layers " + layers +
                             " --snapshot " + path + " " + extra);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
  REQUIRE(img.rows == kSize);
  REQUIRE(img.cols == kSize);
  return img;
}

const json& dump() {
  static const json j = [] {
    const std::string path = folder() + "/arrangement.json";
    const auto r = run_command(kInspect + " " + frame_args() + " --dump " + path);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    std::ifstream in(path);
    return json::parse(in);
  }();
  return j;
}

// `wisp render` of the same frame (PNG, mask, stats), the inspector's reference.
const std::string& rendered() {
  static const std::string dir = [] {
    const std::string out = folder() + "/render";
    const auto r =
        run_command(kWisp + " render " + kScene + " --anim " + wisp::test::simulated(kScene) +
                    " --size 256x256 --frames " + std::to_string(kFrame) + ":" +
                    std::to_string(kFrame + 1) + " --masks -q -o " + out);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    return out;
  }();
  return dir;
}

using Ring = std::vector<cv::Point2d>;

Ring ring(const json& points) {
  Ring out;
  for (const json& p : points) out.emplace_back(p[0].get<double>(), p[1].get<double>());
  return out;
}

// Even-odd crossing test of a point against rings.
bool inside(const std::vector<Ring>& rings, cv::Point2d p) {
  bool in = false;
  for (const Ring& r : rings)
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
      if ((r[i].y > p.y) != (r[j].y > p.y) &&
          p.x < r[j].x + (p.y - r[j].y) * (r[i].x - r[j].x) / (r[i].y - r[j].y))
        in = !in;
  return in;
}

double distance_to_rings(const std::vector<Ring>& rings, cv::Point2d p) {
  double best = 1e300;
  for (const Ring& r : rings)
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const cv::Point2d d = r[i] - r[j];
      const double t = std::clamp((p - r[j]).dot(d) / std::max(d.dot(d), 1e-300), 0.0, 1.0);
      best = std::min(best, cv::norm(p - (r[j] + t * d)));
    }
  return best;
}

// A pixel centre this close to its face's border may fall on either side: the inspector and this
// test compute the crossings of a pixel row in different orders, rounding differently.
constexpr double kBorderMargin = 1e-6;

struct PixelFaces {
  std::vector<int> owner;         // index into dump()["faces"] of the covered face, or -1
  std::vector<bool> near_border;  // the centre is within kBorderMargin of that face's border
};

// The covered face whose polygon contains each pixel's centre: an independent rasterization of
// the dumped faces.
const PixelFaces& pixel_faces() {
  static const PixelFaces out = [] {
    PixelFaces px{std::vector<int>(kSize * kSize, -1), std::vector<bool>(kSize * kSize, false)};
    const json& faces = dump()["faces"];
    for (size_t f = 0; f < faces.size(); ++f) {
      if (!faces[f]["covered"].get<bool>()) continue;
      std::vector<Ring> rings{ring(faces[f]["outer"])};
      for (const json& h : faces[f]["holes"]) rings.push_back(ring(h));
      double lx = kSize, ly = kSize, hx = 0, hy = 0;
      for (const cv::Point2d& p : rings[0])
        lx = std::min(lx, p.x), ly = std::min(ly, p.y), hx = std::max(hx, p.x),
        hy = std::max(hy, p.y);
      const int x0 = std::max(0, int(lx) - 1), x1 = std::min(kSize, int(hx) + 2);
      const int y0 = std::max(0, int(ly) - 1), y1 = std::min(kSize, int(hy) + 2);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const cv::Point2d c(x + 0.5, y + 0.5);
          if (!inside(rings, c)) continue;
          px.owner[y * kSize + x] = int(f);
          px.near_border[y * kSize + x] = distance_to_rings(rings, c) < kBorderMargin;
        }
    }
    return px;
  }();
  return out;
}

cv::Vec3b bgr(const wisp::inspect::Rgb8& c) {
  return {c[2], c[1], c[0]};
}

// Pixels of `img` within `radius` of `p` that have colour `c` (up to `tol` per channel).
bool colour_near(const cv::Mat& img, cv::Point2d p, const wisp::inspect::Rgb8& c, int radius,
                 int tol) {
  const cv::Vec3b want = bgr(c);
  for (int y = int(p.y) - radius; y <= int(p.y) + radius; ++y)
    for (int x = int(p.x) - radius; x <= int(p.x) + radius; ++x) {
      if (x < 0 || y < 0 || x >= img.cols || y >= img.rows) continue;
      const cv::Vec3b v = img.at<cv::Vec3b>(y, x);
      if (std::abs(v[0] - want[0]) <= tol && std::abs(v[1] - want[1]) <= tol &&
          std::abs(v[2] - want[2]) <= tol)
        return true;
    }
  return false;
}

int count_not(const cv::Mat& img, const wisp::inspect::Rgb8& c) {
  int n = 0;
  for (auto it = img.begin<cv::Vec3b>(); it != img.end<cv::Vec3b>(); ++it) n += *it != bgr(c);
  return n;
}

}  // namespace

TEST_CASE("wisp-inspect --dump writes the renderer's arrangement: faces, edges, wisps",
          "[cli][inspect]") {
  const json& d = dump();
  std::ifstream in(rendered() + "/stats.json");
  const json stats = json::parse(in)["frames"][0];
  REQUIRE(stats["frame"] == kFrame);
  // Two programs, one arrangement: the dump's counts are the renderer's.
  CHECK(d["faces"].size() == stats["faces"].get<size_t>());
  CHECK(d["edges"].size() == stats["edges"].get<size_t>());
  CHECK(d["wisps"].size() == stats["wisps"].get<size_t>());
  CHECK(d["stats"]["faces"] == d["faces"].size());
  CHECK(d["width"] == kSize);
  CHECK(d["height"] == kSize);

  // Internally consistent: covered faces have a front wisp that covers them and comes first in
  // the depth order, or show the hair base (no front wisp: none is in front of the head);
  // edges name existing faces; silhouettes separate covered from uncovered.
  size_t covered = 0;
  const json& faces = d["faces"];
  for (const json& f : faces) {
    INFO("face " << f["id"]);
    const int front = f["front"];
    if (!f["covered"].get<bool>()) continue;
    ++covered;
    REQUIRE(f["outer"].size() >= 3);
    if (f["base"].get<bool>()) {
      CHECK(front == -1);
      continue;
    }
    bool covers = false;
    for (const json& c : f["cover"]) covers |= c["wisp"] == front;
    CHECK(covers);
    REQUIRE(!f["depth_order"].empty());
    CHECK(f["depth_order"][0]["wisp"] == front);
    for (size_t k = 1; k < f["depth_order"].size(); ++k)
      CHECK(f["depth_order"][k]["depth"].get<double>() >=
            f["depth_order"][k - 1]["depth"].get<double>());
  }
  CHECK(covered == d["stats"]["covered_faces"].get<size_t>());
  CHECK(covered > 100);
  int silhouettes = 0;
  for (const json& e : d["edges"]) {
    const int l = e["face_left"], r = e["face_right"];
    REQUIRE(l >= 0);
    REQUIRE(r >= 0);
    REQUIRE(size_t(std::max(l, r)) < faces.size());
    if (e["silhouette"].get<bool>()) {
      ++silhouettes;
      CHECK(faces[l]["covered"].get<bool>() != faces[r]["covered"].get<bool>());
    }
  }
  CHECK(silhouettes > 0);
}

TEST_CASE("the faces layer gives each covered face its own colour, the front wisp's hue",
          "[cli][inspect]") {
  const cv::Mat img = snapshot("faces");
  const json& faces = dump()["faces"];
  const PixelFaces& px = pixel_faces();
  // The colour each covered face must have: face_color(front, its number among covered faces),
  // distinct for every face while there are fewer than kFaceCodes.
  REQUIRE(faces.size() < size_t(wisp::inspect::kFaceCodes));
  std::map<int, cv::Vec3b> expected;
  std::map<std::array<std::uint8_t, 3>, int> face_of_colour;
  int number = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    if (faces[f]["covered"].get<bool>()) {
      const cv::Vec3b c = bgr(wisp::inspect::face_color(faces[f]["front"], number++));
      expected[int(f)] = c;
      face_of_colour[{c[0], c[1], c[2]}] = int(f);
    }
  REQUIRE(face_of_colour.size() == expected.size());

  int clear_pixels = 0, agree = 0, stray = 0;
  std::set<int> clear_faces, any_faces, shown_faces;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const cv::Vec3b v = img.at<cv::Vec3b>(y, x);
      if (v != bgr(wisp::inspect::kBackground)) {
        const auto it = face_of_colour.find({v[0], v[1], v[2]});
        if (it == face_of_colour.end())
          ++stray;
        else
          shown_faces.insert(it->second);
      }
      const int f = px.owner[y * kSize + x];
      if (f < 0) continue;
      any_faces.insert(f);
      if (px.near_border[y * kSize + x]) continue;
      ++clear_pixels;
      clear_faces.insert(f);
      agree += v == expected[f];
    }
  REQUIRE(clear_pixels > 1000);
  // Every pixel has the colour of the face that contains its centre, or the background; so
  // there are exactly as many distinct colours as faces owning a pixel centre (faces smaller
  // than a pixel show nowhere), up to centres within kBorderMargin of a border.
  CHECK(stray == 0);
  CHECK(agree == clear_pixels);
  std::vector<int> missing, extra;
  std::set_difference(clear_faces.begin(), clear_faces.end(), shown_faces.begin(),
                      shown_faces.end(), std::back_inserter(missing));
  std::set_difference(shown_faces.begin(), shown_faces.end(), any_faces.begin(), any_faces.end(),
                      std::back_inserter(extra));
  INFO(clear_faces.size() << " faces own a pixel centre, " << shown_faces.size() << " shown");
  CHECK(missing.empty());
  CHECK(extra.empty());
  CHECK(shown_faces.size() <= any_faces.size());
}

TEST_CASE("the coverage layer shows how many wisps cover each face", "[cli][inspect]") {
  const cv::Mat img = snapshot("coverage");
  const json& faces = dump()["faces"];
  const PixelFaces& px = pixel_faces();
  int clear_pixels = 0, agree = 0, background = 0, uncovered = 0, deep = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const cv::Vec3b v = img.at<cv::Vec3b>(y, x);
      const int f = px.owner[y * kSize + x];
      if (f < 0) {
        ++uncovered;
        background += v == bgr(wisp::inspect::kBackground);
        continue;
      }
      if (px.near_border[y * kSize + x]) continue;
      ++clear_pixels;
      const int count = int(faces[f]["cover"].size());
      deep += count >= 3;
      agree += v == bgr(wisp::inspect::coverage_color(count));
    }
  CHECK(agree == clear_pixels);
  CHECK(background == uncovered);
  CHECK(deep > 0);  // hair overlaps itself in this frame: the heat map has more than one level
}

TEST_CASE("the mask and image layers are the renderer's mask and frame", "[cli][inspect]") {
  const cv::Mat mask = snapshot("mask");
  const cv::Mat image = snapshot("image");
  const cv::Mat want_mask = cv::imread(rendered() + "/mask_0010.png", cv::IMREAD_COLOR);
  const cv::Mat want_image = cv::imread(rendered() + "/frame_0010.png", cv::IMREAD_COLOR);
  REQUIRE(want_mask.size() == mask.size());
  REQUIRE(want_image.size() == image.size());
  CHECK(cv::norm(mask, want_mask, cv::NORM_INF) == 0);
  CHECK(cv::countNonZero(mask.reshape(1)) > 1000);
  // Same frame, same warm starts (the inspector replays the frames before it in its block).
  CHECK(cv::norm(image, want_image, cv::NORM_INF) == 0);
}

TEST_CASE("line layers draw what they name", "[cli][inspect]") {
  const json& d = dump();
  using namespace wisp::inspect;

  // Intersection vertices: a dot at (nearly) every one inside the frame.
  const cv::Mat vertices = snapshot("vertices");
  int shown = 0, total = 0;
  for (const json& v : d["vertices"]) {
    const cv::Point2d p(v["p"][0].get<double>(), v["p"][1].get<double>());
    if (!v["intersection"].get<bool>() || p.x < 1 || p.y < 1 || p.x > kSize - 1 || p.y > kSize - 1)
      continue;
    ++total;
    shown += colour_near(vertices, p, kVertexColor, 1, 40);
  }
  REQUIRE(total > 100);
  CHECK(shown >= 0.99 * total);

  // Visible and hidden outline pieces: both colours, visible ones along visible edge sources.
  const cv::Mat visibility = snapshot("visibility");
  int visible_ok = 0, visible_total = 0;
  for (const json& e : d["edges"])
    for (const json& s : e["sources"]) {
      if (s["wisp"].get<int>() < 0 || !s["visible"].get<bool>()) continue;
      const cv::Point2d mid((e["a"][0].get<double>() + e["b"][0].get<double>()) / 2,
                            (e["a"][1].get<double>() + e["b"][1].get<double>()) / 2);
      if (mid.x < 1 || mid.y < 1 || mid.x > kSize - 1 || mid.y > kSize - 1) continue;
      ++visible_total;
      visible_ok += colour_near(visibility, mid, kVisibleColor, 1, 60);
    }
  REQUIRE(visible_total > 100);
  // A visible piece can be drawn over by a hidden one crossing it at its middle.
  CHECK(visible_ok >= 0.9 * visible_total);
  int hidden = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      hidden += colour_near(visibility, {x + 0.5, y + 0.5}, kHiddenColor, 0, 30);
  CHECK(hidden > 50);
  // Depth seams: edges with only seam sources, in their own colour. Those of 1 px and more (70 %
  // show it at their middle: a seam ends at outlines, and visible pieces are drawn over it).
  int seam_ok = 0, seam_total = 0;
  for (const json& e : d["edges"]) {
    bool seam = !e["sources"].empty();
    for (const json& s : e["sources"]) seam &= s["side"].get<std::string>() == "seam";
    const cv::Point2d a(e["a"][0].get<double>(), e["a"][1].get<double>()),
        b(e["b"][0].get<double>(), e["b"][1].get<double>()), mid = (a + b) / 2;
    if (!seam || cv::norm(b - a) < 1 || mid.x < 1 || mid.y < 1 || mid.x > kSize - 1 ||
        mid.y > kSize - 1)
      continue;
    ++seam_total;
    seam_ok += colour_near(visibility, mid, wisp::inspect::kSeamColor, 1, 60);
  }
  REQUIRE(seam_total > 10);
  CHECK(seam_ok >= 0.6 * seam_total);

  // Outlines, centre curves and ink draw something, and different things.
  const cv::Mat outlines = snapshot("outlines"), curves = snapshot("curves"), ink = snapshot("ink");
  CHECK(count_not(outlines, kBackground) > 2000);
  CHECK(count_not(curves, kBackground) > 500);
  CHECK(count_not(ink, kBackground) > 500);
  CHECK(cv::norm(outlines, curves, cv::NORM_L1) > 0);
  CHECK(cv::norm(curves, ink, cv::NORM_L1) > 0);
}

TEST_CASE("the solver layers show the constraints and a shrinking residual", "[cli][inspect]") {
  const cv::Mat constraints = snapshot("constraints");
  CHECK(count_not(constraints, wisp::inspect::kBackground) > 500);
  // Residual after the FMG start against after the last cycle: the picture darkens (log scale).
  const cv::Mat first = snapshot("residual", "--residual-step 0");
  const cv::Mat last = snapshot("residual");
  CHECK(count_not(first, wisp::inspect::kBackground) > 100);
  CHECK(cv::sum(first)[0] + cv::sum(first)[1] + cv::sum(first)[2] >
        cv::sum(last)[0] + cv::sum(last)[1] + cv::sum(last)[2]);
}

TEST_CASE("wisp-inspect refuses bad input with one line and exit code 2", "[cli][inspect]") {
  const std::string out = folder() + "/bad.png";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {frame_args(500) + " --snapshot " + out, "--frame 500"},
      {frame_args(-1) + " --snapshot " + out, "--frame"},
      {frame_args() + " --layers faces,bogus --snapshot " + out, "bogus"},
      {frame_args() + " --layers , --snapshot " + out, "--layers"},
      {frame_args() + " --snapshot " + folder() + "/nope/x.png", "does not exist"},
      {frame_args() + " --snapshot " + folder() + "/x.jpg", "expected a .png"},
      {frame_args() + " --pick 3", "--pick"},
      {frame_args() + " --frame 2 --snapshot " + out, "--frame"},  // given twice
      {frame_args() + " --zoom 2 --snapshot " + out, "--zoom"},
      {WISP_SOURCE_DIR "/data/scenes/missing.json --snapshot " + out, "missing.json"},
  };
  for (const auto& [args, needle] : cases) {
    INFO(args);
    const auto r = run_command(kInspect + " " + args);
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(needle) != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK(!fs::exists(out));
  }
  // A window on a display nobody serves, or on none: refused before Qt would abort.
  for (const std::string env :
       {"env DISPLAY=:987 WAYLAND_DISPLAY= ", "env DISPLAY=: WAYLAND_DISPLAY= ",
        "env -u DISPLAY -u WAYLAND_DISPLAY "}) {
    const auto r = run_command(env + kInspect + " " + frame_args());
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("DISPLAY") != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
}

namespace {

// The pixels of an X window dump (xwd): the raw image bytes after the header and colour map.
std::string xwd_pixels(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes(std::istreambuf_iterator<char>(in), {});
  const auto field = [&](int k) {  // header fields are big-endian 32-bit words
    REQUIRE(bytes.size() >= size_t(4 * k + 4));
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data()) + 4 * k;
    return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3];
  };
  const size_t header = field(0), height = field(5), bytes_per_line = field(12),
               colours = field(19);
  const size_t start = header + 12 * colours;
  REQUIRE(bytes.size() >= start + height * bytes_per_line);
  return bytes.substr(start, height * bytes_per_line);
}

}  // namespace

TEST_CASE("the window opens under Xvfb, a key toggles a layer, a click picks", "[cli][window]") {
  for (const char* tool : {"Xvfb", "xdotool", "xwd"}) {
    INFO(tool << " is missing: scripts/install-deps installs it");
    REQUIRE(run_command(std::string("command -v ") + tool).exit_code == 0);
  }
  const std::string dir = fresh_folder("inspect_window");
  // One script: a private X server (the display number it picks itself), the app, key presses
  // and screenshots between them. Each wait is bounded; on failure the script names the step.
  const std::string script = R"(set -u
cd ")" + dir + R"("
Xvfb -displayfd 3 -screen 0 1400x900x24 -nolisten tcp 3>display.txt 2>xvfb.log &
XVFB=$!
trap 'kill $APP $XVFB 2>/dev/null; wait 2>/dev/null' EXIT
for i in $(seq 300); do [ -s display.txt ] && break; sleep 0.1; done
[ -s display.txt ] || { echo "Xvfb did not start"; exit 1; }
export DISPLAY=:$(cat display.txt)
)" + kInspect + " " + frame_args() +
                             R"( --no-opengl >app.log 2>&1 &
APP=$!
wait_for() {  # a line in the app's log
  for i in $(seq 600); do grep -q "$1" app.log && return 0; kill -0 $APP 2>/dev/null || break; sleep 0.1; done
  echo "no '$1' from the app:"; cat app.log; exit 1
}
wait_for "^ready:"
WID=$(xdotool search --sync --name "wisp-inspect" | head -1)
[ -n "$WID" ] || { echo "no window"; exit 1; }
xdotool windowfocus --sync $WID
sleep 0.5
xwd -root -silent >before.xwd
xdotool key --clearmodifiers f
wait_for "layer faces on"
sleep 0.5
xwd -root -silent >after.xwd
xdotool mousemove --window $WID 300 300 click 1
wait_for "^pick: "
xdotool key q
for i in $(seq 100); do kill -0 $APP 2>/dev/null || break; sleep 0.1; done
wait $APP; echo "app exit $?"
)";
  { std::ofstream(dir + "/run.sh") << script; }
  const auto r = run_command("bash " + dir + "/run.sh 3>&-");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("app exit 0") != std::string::npos);

  const std::string before = xwd_pixels(dir + "/before.xwd");
  const std::string after = xwd_pixels(dir + "/after.xwd");
  REQUIRE(before.size() == after.size());
  // The window drew a picture (the X root alone is one colour) ...
  std::set<char> values(before.begin(), before.end());
  CHECK(values.size() > 20);
  // ... and turning the faces layer on changed a good part of it (the hair area at least).
  size_t changed = 0;
  for (size_t i = 0; i < before.size(); i += 4) changed += before.compare(i, 4, after, i, 4) != 0;
  CHECK(changed > 5000);
}
