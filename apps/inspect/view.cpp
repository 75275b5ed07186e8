// Window state, events and the window's picture (see inspect_view.hpp).
#include "apps/inspect/view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/highgui.hpp>
#include <opencv2/imgproc.hpp>

namespace wisp::inspect {
namespace {

using Vec2 = Eigen::Vector2d;

// X11 keysyms, as highgui's Qt and GTK backends return them from waitKeyEx.
constexpr int kKeyLeft = 0xff51, kKeyRight = 0xff53, kKeyPageUp = 0xff55, kKeyPageDown = 0xff56;
constexpr int kKeyHome = 0xff50, kKeyEnd = 0xff57, kKeyReturn = 0xff0d, kKeyKpEnter = 0xff8d;
constexpr int kKeyEscape = 27, kKeyBackspace = 8;
constexpr double kWheelStep = 1.25;  // zoom factor per wheel notch
constexpr double kMinZoom = 0.05, kMaxZoom = 256;
constexpr int kDragThreshold = 3;  // canvas pixels before a press becomes a drag

const cv::Scalar kText(235, 235, 235), kDim(150, 150, 150), kAccent(0, 200, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.42;
constexpr int kLine = 17;

std::string format(const char* fmt, double a = 0, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

Action go_to(WindowState& s, int frame) {
  frame = std::clamp(frame, 0, s.frame_count - 1);
  if (frame == s.frame) return Action::Redraw;
  s.frame = frame;
  s.message = "frame " + std::to_string(frame);
  return Action::LoadFrame;
}

void zoom_about(WindowState& s, const Vec2& canvas_point, double factor) {
  const double zoom = std::clamp(s.view.zoom * factor, kMinZoom, kMaxZoom);
  const Vec2 p = s.view.to_frame(canvas_point);
  s.view.zoom = zoom;
  s.view.offset = canvas_point - p * zoom;
  s.message = format("zoom %.2fx", zoom);
}

Vec2 area_centre(const WindowState& s) {
  return {0.5 * s.area.width, 0.5 * s.area.height};
}

// Text wrapped to `width` pixels at spaces; continuation lines are indented.
std::vector<std::string> wrap(const std::string& text, int width) {
  const auto fits = [&](const std::string& t) {
    int base = 0;
    return cv::getTextSize(t, kFont, kFontScale, 1, &base).width <= width;
  };
  const size_t lead = std::min(text.find_first_not_of(' '), text.size());
  std::vector<std::string> out;
  std::string line = text.substr(0, lead);
  bool empty = true;  // no word on `line` yet
  size_t i = lead;
  while (i < text.size()) {
    size_t j = text.find(' ', i);
    if (j == std::string::npos) j = text.size();
    const std::string word = text.substr(i, j - i);
    if (!empty && !fits(line + " " + word)) {
      out.push_back(line);
      line = std::string(lead + 2, ' ') + word;
    } else {
      line += (empty ? "" : " ") + word;
    }
    empty = false;
    i = j + 1;
  }
  out.push_back(line);
  return out;
}

struct Writer {
  cv::Mat& img;
  int x, y, width;
  void line(const std::string& text, const cv::Scalar& color = kText) {
    for (const std::string& l : wrap(text, width)) {
      y += kLine;
      if (y > img.rows - 4) return;
      cv::putText(img, l, {x, y}, kFont, kFontScale, color, 1, cv::LINE_AA);
    }
  }
  void gap() { y += kLine / 2; }
  void swatch(const Rgb8& c, const std::string& label) {
    y += kLine;
    if (y > img.rows - 4) return;
    cv::rectangle(img, {x, y - 11}, {x + 14, y + 1}, cv::Scalar(c[2], c[1], c[0]), cv::FILLED);
    cv::putText(img, label, {x + 20, y}, kFont, kFontScale, kText, 1, cv::LINE_AA);
  }
};

void draw_legends(Writer& w, const InspectFrame& f, const WindowState& s) {
  const LayerSet& l = s.layers;
  if (l.has(Layer::Coverage)) {
    w.line("coverage count:", kDim);
    for (int k : {1, 2, 4, 8, kCoverageLevels})
      w.swatch(coverage_color(k),
               std::to_string(k) + (k == kCoverageLevels ? " or more wisps" : " wisps"));
  }
  if (l.has(Layer::Residual)) {
    const int step = residual_step(f, l);
    const auto& hist = f.result.solve.residual_history;
    if (step < 0) {
      w.line("residual: nothing solved in this frame", kDim);
    } else {
      w.line((step == 0 ? std::string("residual after the FMG start")
                        : "residual after cycle " + std::to_string(step)) +
                 format(" (step %.0f of %.0f)", step + 1, double(f.residual.size())) +
                 (size_t(step) < hist.size() ? format(", relative %.2e", hist[step]) : ""),
             kDim);
      for (double e = kResidualLog10Max; e >= kResidualLog10Min; e -= 2)
        w.swatch(residual_color(float(std::pow(10.0, e))), format("|r| = 1e%.0f", e));
    }
  }
  if (l.has(Layer::Visibility)) {
    w.swatch(kVisibleColor, "visible outline piece");
    w.swatch(kHiddenColor, "hidden outline piece");
    w.swatch(kSeamColor, "depth seam (two wisps, or hair and body, swap depth)");
  }
  if (l.has(Layer::Curves)) {
    w.swatch(kOnCurveColor, "on-curve control point");
    w.swatch(kHandleColor, "off-curve control point");
  }
  if (l.has(Layer::Vertices)) w.swatch(kVertexColor, "intersection vertex");
  if (l.has(Layer::Ink) && f.result.picture.ink.empty()) {
    w.swatch(kSilhouetteColor, "silhouette");
    w.swatch(kOcclusionColor, "occlusion boundary");
  }
}

void draw_panel(cv::Mat& img, const InspectFrame& f, const WindowState& s,
                const std::string& title) {
  const cv::Rect panel(img.cols - kPanelWidth, 0, kPanelWidth, img.rows);
  img(panel).setTo(cv::Scalar(24, 24, 24));
  Writer w{img, panel.x + 12, 4, kPanelWidth - 24};
  const render::FrameResult& r = f.result;
  const auto& st = r.arrangement.stats;
  w.line("wisp-inspect  " + title, kAccent);
  w.line(format("frame %.0f of %.0f, t = %.3f s", f.index, s.frame_count - 1, f.time) +
         format(", %.0fx%.0f px", f.width(), f.height()));
  w.line(format("wisps %.0f, faces %.0f (%.0f covered)", double(r.wisps.size()), st.faces,
                st.covered_faces));
  w.line(format("edges %.0f, vertices %.0f, intersections %.0f", st.edges, st.vertices,
                st.intersections));
  if (r.curves.empty())
    w.line("solver: nothing to solve", kDim);
  else
    w.line(format("solver: %.0f cycles, residual %.2e, ", r.solve.cycles, r.solve.final_residual) +
           (r.solve.converged ? "converged" : "NOT converged"));
  w.line(format("times: arrangement %.1f ms, solve %.1f ms", r.time.arrangement, r.time.solve),
         kDim);
  std::string on;
  for (const LayerInfo& info : layer_table())
    if (s.layers.has(info.layer)) on += std::string(on.empty() ? "" : ", ") + info.name;
  w.line("layers: " + (on.empty() ? std::string("none") : on));
  w.line(format("zoom %.2fx", s.view.zoom), kDim);
  if (s.prompting) w.line("go to frame: " + s.prompt + "_  (Enter, Esc)", kAccent);
  if (!s.message.empty()) w.line(s.message, kDim);
  w.gap();
  draw_legends(w, f, s);
  w.gap();
  if (s.pick.empty()) {
    w.line("click a point to pick it", kDim);
  } else {
    for (const std::string& line : s.pick) w.line(line);
  }
  cv::putText(img, "h: help   q: quit", {panel.x + 12, img.rows - 10}, kFont, kFontScale, kDim, 1,
              cv::LINE_AA);
}

void draw_help(cv::Mat& img, const WindowState& s) {
  const std::vector<std::string> lines = help_lines(s.layers);
  const cv::Rect box(10, 10, std::min(s.area.width - 20, 560),
                     std::min(s.area.height - 20, int(lines.size()) * kLine + 16));
  if (box.width <= 0 || box.height <= 0) return;
  cv::Mat roi = img(box);
  roi = roi * 0.25;  // darken what is under the box
  Writer w{img, box.x + 10, box.y, box.width - 20};
  for (const std::string& line : lines) w.line(line, line.rfind(" ", 0) == 0 ? kText : kAccent);
}

}  // namespace

ViewTransform fit_view(cv::Size area, int width, int height) {
  ViewTransform v;
  if (width <= 0 || height <= 0) return v;
  v.zoom = std::min(double(area.width) / width, double(area.height) / height);
  v.offset = Vec2(0.5 * (area.width - v.zoom * width), 0.5 * (area.height - v.zoom * height));
  return v;
}

cv::Size default_area(int width, int height, int max_side) {
  const double s = std::min(double(max_side) / width, double(max_side) / height);
  return {std::max(1, int(std::lround(width * s))), std::max(1, int(std::lround(height * s)))};
}

WindowState initial_state(int first_frame, int frame_count, int width, int height, cv::Size area,
                          const LayerSet& layers) {
  WindowState s;
  s.frame = first_frame;
  s.frame_count = std::max(1, frame_count);
  s.frame_width = width;
  s.frame_height = height;
  s.area = area;
  s.layers = layers;
  s.view = fit_view(area, width, height);
  return s;
}

Action handle_key(WindowState& s, int key) {
  if (key < 0) return Action::None;
  if (s.prompting) {
    if (key >= '0' && key <= '9' && s.prompt.size() < 7) {
      s.prompt += char(key);
    } else if (key == kKeyBackspace || key == 0xff08) {
      if (!s.prompt.empty()) s.prompt.pop_back();
    } else if (key == '\r' || key == '\n' || key == kKeyReturn || key == kKeyKpEnter) {
      s.prompting = false;
      if (s.prompt.empty()) return Action::Redraw;
      const int k = std::stoi(s.prompt);
      if (k >= s.frame_count) {
        s.message = "no frame " + s.prompt + " (0 to " + std::to_string(s.frame_count - 1) + ")";
        return Action::Redraw;
      }
      return go_to(s, k);
    } else if (key == kKeyEscape) {
      s.prompting = false;
    }
    return Action::Redraw;
  }
  for (const LayerInfo& info : layer_table())
    if (key == info.key) {
      s.layers.toggle(info.layer);
      s.message = std::string("layer ") + info.name + (s.layers.has(info.layer) ? " on" : " off");
      return Action::Redraw;
    }
  switch (key) {
    case 'q':
    case kKeyEscape:
      return Action::Quit;
    case 'h':
      s.help = !s.help;
      s.message = s.help ? "help on" : "help off";
      return Action::Redraw;
    case kKeyRight:
    case '.':
      return go_to(s, s.frame + 1);
    case kKeyLeft:
    case ',':
      return go_to(s, s.frame - 1);
    case kKeyPageDown:
      return go_to(s, s.frame + 10);
    case kKeyPageUp:
      return go_to(s, s.frame - 10);
    case kKeyHome:
      return go_to(s, 0);
    case kKeyEnd:
      return go_to(s, s.frame_count - 1);
    case 'g':
      s.prompting = true;
      s.prompt.clear();
      return Action::Redraw;
    case ']':
    case '[': {
      if (s.residual_steps <= 0) {
        s.message = "no solver steps in this frame";
        return Action::Redraw;
      }
      const int last = s.residual_steps - 1;
      const int step = s.layers.residual_step < 0 ? last : std::min(s.layers.residual_step, last);
      s.layers.residual_step = std::clamp(step + (key == ']' ? 1 : -1), 0, last);
      s.layers.set(Layer::Residual);
      s.message = "residual step " + std::to_string(s.layers.residual_step + 1) + " of " +
                  std::to_string(s.residual_steps);
      return Action::Redraw;
    }
    case '+':
    case '=':
      zoom_about(s, area_centre(s), kWheelStep);
      return Action::Redraw;
    case '-':
      zoom_about(s, area_centre(s), 1 / kWheelStep);
      return Action::Redraw;
    case '0':
      s.view = fit_view(s.area, s.frame_width, s.frame_height);
      s.message = "view reset";
      return Action::Redraw;
    case 's':
      return Action::Save;
    default:
      return Action::None;
  }
}

Action handle_mouse(WindowState& s, int event, int x, int y, int flags) {
  const Vec2 q(x, y);
  const bool in_area = x >= 0 && y >= 0 && x < s.area.width && y < s.area.height;
  switch (event) {
    case cv::EVENT_MOUSEWHEEL: {
      if (!in_area) return Action::None;
      const int delta = cv::getMouseWheelDelta(flags);
      if (delta == 0) return Action::None;
      zoom_about(s, q, std::pow(kWheelStep, delta / 120.0));
      return Action::Redraw;
    }
    case cv::EVENT_LBUTTONDOWN:
      s.press = q;
      s.dragging = false;
      return Action::None;
    case cv::EVENT_MOUSEMOVE: {
      if (!s.press || !(flags & cv::EVENT_FLAG_LBUTTON)) return Action::None;
      if (!s.dragging && (q - *s.press).cwiseAbs().maxCoeff() < kDragThreshold) return Action::None;
      s.dragging = true;
      s.view.offset += q - *s.press;
      s.press = q;
      s.message = "pan";
      return Action::Redraw;
    }
    case cv::EVENT_LBUTTONUP: {
      const bool click = s.press && !s.dragging;
      s.press.reset();
      s.dragging = false;
      if (!click || !in_area) return Action::None;
      s.pick_point = s.view.to_frame(q + Vec2(0.5, 0.5));  // the centre of the clicked pixel
      return Action::Pick;
    }
    default:
      return Action::None;
  }
}

std::vector<std::string> help_lines(const LayerSet& layers) {
  std::vector<std::string> out{"Layers (key, * when on)"};
  for (const LayerInfo& info : layer_table())
    out.push_back(std::string(" ") + info.key + "  " + (layers.has(info.layer) ? "* " : "   ") +
                  info.name + ": " + info.title);
  const char* nav[] = {
      "Frames",
      " Right or .  next frame;  Left or ,  previous frame",
      " PageDown / PageUp  10 frames on / back;  Home / End  first / last",
      " g, digits, Enter  go to a frame (Esc cancels)",
      " [ ]  residual layer: previous / next solver step",
      "View",
      " mouse wheel, + -  zoom;  drag  pan;  0  reset the view",
      " click  pick: face, covering wisps, nearest edge, wisp (panel and stdout)",
      " s  save the window as inspect_frame_NNNN.png;  h  help;  q or Esc  quit",
  };
  out.insert(out.end(), std::begin(nav), std::end(nav));
  return out;
}

cv::Mat compose_window(const InspectFrame& frame, const WindowState& s, const std::string& title) {
  const int height = std::max(s.area.height, kMinCanvasHeight);
  cv::Mat img(height, s.area.width + kPanelWidth, CV_8UC3,
              cv::Scalar(kBackground[2], kBackground[1], kBackground[0]));
  draw_layers(frame, s.layers, s.view, s.area).copyTo(img(cv::Rect({0, 0}, s.area)));
  if (s.pick_point) {
    const Vec2 q = s.view.to_canvas(*s.pick_point);
    cv::drawMarker(img, cv::Point(int(std::lround(q.x())), int(std::lround(q.y()))),
                   cv::Scalar(255, 255, 255), cv::MARKER_CROSS, 15, 1, cv::LINE_AA);
  }
  if (s.help) draw_help(img, s);
  draw_panel(img, frame, s, title);
  return img;
}

}  // namespace wisp::inspect
