// The inspector window's behaviour without a window (apps/inspect_view.hpp): keys toggle layers
// and move between frames, the frame prompt checks its range, the wheel zooms about the pointer,
// a drag pans, a click picks the frame point under it, the layer names parse strictly.
#include <catch2/catch.hpp>
#include <opencv2/highgui.hpp>

#include "apps/inspect/layers.hpp"
#include "apps/inspect/view.hpp"

using namespace wisp::inspect;

namespace {

constexpr int kEnter = '\r', kRight = 0xff53, kEnd = 0xff57;

WindowState state() {
  LayerSet layers;
  layers.set(Layer::Image);
  return initial_state(3, 20, 256, 128, {512, 512}, layers);
}

// Where frame point p is on the canvas, and back.
Eigen::Vector2d canvas(const WindowState& s, Eigen::Vector2d p) {
  return s.view.to_canvas(p);
}

}  // namespace

TEST_CASE("inspector: the initial view fits the frame, centred", "[inspect][view]") {
  const WindowState s = state();
  // 256x128 in 512x512: zoom 2, centred vertically.
  CHECK(s.view.zoom == Approx(2));
  CHECK(canvas(s, {0, 0}).x() == Approx(0));
  CHECK(canvas(s, {128, 64}).y() == Approx(256));
  CHECK(s.frame == 3);
  CHECK(default_area(256, 128) == cv::Size(800, 400));
}

TEST_CASE("inspector: layer keys toggle their layer and say so", "[inspect][view]") {
  WindowState s = state();
  for (const LayerInfo& info : layer_table()) {
    INFO(info.name);
    const bool was = s.layers.has(info.layer);
    CHECK(handle_key(s, info.key) == Action::Redraw);
    CHECK(s.layers.has(info.layer) == !was);
    CHECK(s.message == std::string("layer ") + info.name + (was ? " off" : " on"));
  }
  // Every layer has its own key, and none of them is a navigation key.
  std::string keys;
  for (const LayerInfo& info : layer_table()) keys += info.key;
  std::string sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
  CHECK(keys.find_first_of("qhgs0+-=[].,") == std::string::npos);
  CHECK(handle_key(s, 'q') == Action::Quit);
  CHECK(handle_key(s, -1) == Action::None);
}

TEST_CASE("inspector: frame keys and the frame prompt", "[inspect][view]") {
  WindowState s = state();
  CHECK(handle_key(s, kRight) == Action::LoadFrame);
  CHECK(s.frame == 4);
  CHECK(handle_key(s, ',') == Action::LoadFrame);
  CHECK(s.frame == 3);
  CHECK(handle_key(s, kEnd) == Action::LoadFrame);
  CHECK(s.frame == 19);
  CHECK(handle_key(s, '.') == Action::Redraw);  // already the last: nothing to load
  CHECK(s.frame == 19);

  for (int key : {'g', '1', '2'}) handle_key(s, key);
  CHECK(handle_key(s, kEnter) == Action::LoadFrame);
  CHECK(s.frame == 12);
  CHECK(!s.prompting);

  for (int key : {'g', '9', '9'}) handle_key(s, key);
  CHECK(handle_key(s, kEnter) != Action::LoadFrame);
  CHECK(s.frame == 12);
  CHECK(s.message.find("no frame 99") != std::string::npos);
}

TEST_CASE("inspector: the wheel zooms about the pointer, a drag pans, a click picks",
          "[inspect][view]") {
  WindowState s = state();
  const Eigen::Vector2d pointer(100, 300);
  const Eigen::Vector2d under = s.view.to_frame(pointer);
  CHECK(handle_mouse(s, cv::EVENT_MOUSEWHEEL, 100, 300, 120 << 16) == Action::Redraw);
  CHECK(s.view.zoom == Approx(2 * 1.25));
  CHECK((s.view.to_frame(pointer) - under).norm() < 1e-9);  // the point stays under the pointer
  handle_mouse(s, cv::EVENT_MOUSEWHEEL, 100, 300, -(120 << 16));
  CHECK(s.view.zoom == Approx(2));

  // Drag: the frame moves with the mouse; no pick at the release.
  const Eigen::Vector2d before = s.view.offset;
  handle_mouse(s, cv::EVENT_LBUTTONDOWN, 200, 200, cv::EVENT_FLAG_LBUTTON);
  CHECK(handle_mouse(s, cv::EVENT_MOUSEMOVE, 230, 190, cv::EVENT_FLAG_LBUTTON) == Action::Redraw);
  CHECK((s.view.offset - before - Eigen::Vector2d(30, -10)).norm() < 1e-12);
  CHECK(handle_mouse(s, cv::EVENT_LBUTTONUP, 230, 190, 0) == Action::None);

  // Click: the frame point at the clicked pixel's centre.
  handle_mouse(s, cv::EVENT_LBUTTONDOWN, 40, 260, cv::EVENT_FLAG_LBUTTON);
  handle_mouse(s, cv::EVENT_MOUSEMOVE, 41, 260, cv::EVENT_FLAG_LBUTTON);  // a tremble, not a drag
  CHECK(handle_mouse(s, cv::EVENT_LBUTTONUP, 41, 260, 0) == Action::Pick);
  REQUIRE(s.pick_point);
  CHECK((*s.pick_point - s.view.to_frame({41.5, 260.5})).norm() < 1e-12);

  CHECK(handle_key(s, '0') == Action::Redraw);
  CHECK(s.view.zoom == Approx(2));
  CHECK(s.view.offset.x() == Approx(0));
}

TEST_CASE("inspector: layer names parse strictly", "[inspect][view]") {
  const std::vector<Layer> layers = parse_layers("faces,curves,mask");
  CHECK(layers == std::vector<Layer>{Layer::Faces, Layer::Curves, Layer::Mask});
  CHECK_THROWS_WITH(parse_layers("faces,bogus"), Catch::Contains("bogus"));
  CHECK_THROWS(parse_layers(""));
  CHECK_THROWS(parse_layers(","));
}
