// `wisp-inspect scene.json`: the debug app. Renders a frame of the scene as `wisp render` does
// and opens an OpenCV highgui window on it with toggleable layers, frame navigation, zoom, pan
// and picking (inspect_view.hpp has the behaviour, inspect_layers.hpp the drawing). Headless
// modes for scripts, docs and tests: --snapshot draws chosen layers to a PNG, --dump writes the
// frame's arrangement as JSON, --pick describes a point on stdout. Bad input is a one-line error
// naming the option or file, exit code 2, and nothing written.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <opencv2/highgui.hpp>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <stdexcept>
#include <string>

#include "apps/cli/cli_error.hpp"
#include "apps/inspect/inspected_frame.hpp"
#include "apps/inspect/layers.hpp"
#include "apps/inspect/query.hpp"
#include "apps/inspect/view.hpp"
#include "apps/render/image_size.hpp"
#include "apps/render/progress.hpp"
#include "apps/render/scene_frames.hpp"
#include "io/atomic_file.hpp"

namespace wisp::inspect {
namespace {

namespace fs = std::filesystem;

struct Args {
  std::string scene, anim, size, layers, snapshot, dump, pick, window;
  int frame = 0;
  int residual_step = -1;
  bool no_opengl = false;
};

// The folder of an output file must exist: checked before any work is done.
void check_output(const std::string& option, const std::string& path, const std::string& ext) {
  const fs::path p(path);
  if (p.extension() != ext)
    throw std::invalid_argument(option + " " + path + ": expected a " + ext + " file");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir))
    throw std::invalid_argument(option + " " + path + ": the folder " + dir.string() +
                                " does not exist");
}

// Qt aborts the process when it cannot reach the display, so look first: DISPLAY must be a
// display name and, for a local display (":N"), its socket must exist.
void check_display() {
  if (const char* w = std::getenv("WAYLAND_DISPLAY"); w && *w) return;
  const char* display = std::getenv("DISPLAY");
  const std::string hint = "; use --snapshot, --dump or --pick to work without a window";
  if (!display || !*display)
    throw std::runtime_error("no display to open a window on (DISPLAY is not set)" + hint);
  std::smatch m;
  const std::string d = display;
  if (!std::regex_match(d, m, std::regex(R"(([^:]*):(\d+)(\.\d+)?)")))
    throw std::runtime_error("DISPLAY " + d + ": not a display name (expected [host]:N)" + hint);
  const bool local = m[1].str().empty() || m[1].str() == "unix";
  if (local && !fs::exists("/tmp/.X11-unix/X" + m[2].str()))
    throw std::runtime_error("DISPLAY " + d + ": no X server listens there (no /tmp/.X11-unix/X" +
                             m[2].str() + ")" + hint);
}

void write_png(const fs::path& path, const cv::Mat& img) {
  io::write_atomically(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), img, {cv::IMWRITE_PNG_COMPRESSION, 9}))
      throw std::runtime_error(path.string() + ": cannot write the PNG file");
  });
}

void say(const std::string& line) {
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

void print_pick(const std::vector<std::string>& lines) {
  for (const std::string& l : lines) say("pick: " + l);
}

struct MouseEvent {
  int event, x, y, flags;
};

void on_mouse(int event, int x, int y, int flags, void* queue) {
  static_cast<std::vector<MouseEvent>*>(queue)->push_back({event, x, y, flags});
}

void run_window(FrameSource& source, InspectFrame frame, const LayerSet& layers, cv::Size area,
                const std::string& title, bool opengl) {
  const std::string name = "wisp-inspect: " + title;
  // The OpenGL viewport passes the mouse wheel to us; the plain Qt viewport would also zoom the
  // picture itself on every wheel event (its own zoom, which we cannot turn off).
  bool gl = false;
  if (opengl) try {
      cv::namedWindow(name, cv::WINDOW_AUTOSIZE | cv::WINDOW_OPENGL | cv::WINDOW_GUI_NORMAL);
      gl = true;
    } catch (const cv::Exception&) {
    }
  if (!gl) cv::namedWindow(name, cv::WINDOW_AUTOSIZE | cv::WINDOW_GUI_NORMAL);
  std::vector<MouseEvent> mouse;
  cv::setMouseCallback(name, on_mouse, &mouse);

  WindowState s =
      initial_state(frame.index, source.frame_count(), frame.width(), frame.height(), area, layers);
  s.residual_steps = int(frame.residual.size());
  bool dirty = true, shown = false;
  std::string said;  // the last message printed: drags and picks keep it, so print it once
  for (;;) {
    if (dirty) {
      cv::imshow(name, compose_window(frame, s, title));
      dirty = false;
    }
    const int key = cv::waitKeyEx(20);
    if (!shown) {
      say("ready: frame " + std::to_string(frame.index));
      shown = true;
    }
    if (cv::getWindowProperty(name, cv::WND_PROP_VISIBLE) < 1) break;  // closed by the user
    if (key >= 0) said.clear();  // a key press says its message even when it repeats
    std::vector<Action> actions{handle_key(s, key)};
    for (const MouseEvent& m : std::vector<MouseEvent>(std::move(mouse)))
      actions.push_back(handle_mouse(s, m.event, m.x, m.y, m.flags));
    mouse.clear();
    for (const Action a : actions) {
      switch (a) {
        case Action::None:
          continue;
        case Action::Quit:
          cv::destroyWindow(name);
          return;
        case Action::LoadFrame:
          frame = source.render(s.frame);
          s.residual_steps = int(frame.residual.size());
          if (s.pick_point) s.pick = describe_point(frame, *s.pick_point);
          break;
        case Action::Pick:
          s.pick = describe_point(frame, *s.pick_point);
          print_pick(s.pick);
          break;
        case Action::Save: {
          char file[64];
          std::snprintf(file, sizeof file, "inspect_frame_%04d.png", frame.index);
          write_png(file, compose_window(frame, s, title));
          s.message = std::string("saved ") + file;
          break;
        }
        case Action::Redraw:
          break;
      }
      if (!s.message.empty() && s.message != said) say(said = s.message);
      dirty = true;
    }
  }
}

void run(const Args& a) {
  // Arguments first, so their errors come before any work.
  LayerSet layers;
  for (const Layer l : parse_layers(a.layers.empty() ? "image" : a.layers)) layers.set(l);
  layers.residual_step = a.residual_step;
  int width = 0, height = 0;
  if (!a.size.empty()) std::tie(width, height) = render::parse_size("--size", a.size);
  cv::Size area;
  if (!a.window.empty()) {
    const auto [w, h] = render::parse_size("--window", a.window);
    area = {w, h};
  }
  std::optional<Eigen::Vector2d> pick;
  if (!a.pick.empty()) {
    std::smatch m;
    const std::string number = R"(\s*([-+]?\d+(?:\.\d*)?)\s*)";
    if (!std::regex_match(a.pick, m, std::regex(number + "," + number)))
      throw std::invalid_argument("--pick: expected X,Y in frame pixels, got '" + a.pick + "'");
    pick = Eigen::Vector2d(std::stod(m[1]), std::stod(m[2]));
  }
  if (a.frame < 0)
    throw std::invalid_argument("--frame " + std::to_string(a.frame) + ": must be 0 or more");
  if (!a.snapshot.empty()) check_output("--snapshot", a.snapshot, ".png");
  if (!a.dump.empty()) check_output("--dump", a.dump, ".json");
  const bool headless = !a.snapshot.empty() || !a.dump.empty() || pick;
  if (!headless) check_display();

  render::SceneFramesOptions options;
  options.anim = a.anim;
  options.width = width;
  options.height = height;
  std::unique_ptr<render::ProgressBar> bar;
  options.sim_progress = [&bar](int done, int total) {
    if (!bar) bar = std::make_unique<render::ProgressBar>("simulate", total);
    bar->update(done);
  };
  render::SceneFrames frames = render::load_scene_frames(a.scene, options);
  if (bar) bar->finish();
  const int n = frames.frame_count();
  if (a.frame >= n)
    throw std::invalid_argument("--frame " + std::to_string(a.frame) + ": the animation has " +
                                std::to_string(n) + " frames (0 to " + std::to_string(n - 1) + ")");

  FrameSource source(std::move(frames));
  InspectFrame frame = source.render(a.frame);
  if (headless) {
    if (!a.snapshot.empty())
      write_png(a.snapshot,
                draw_layers(frame, layers, ViewTransform{}, {frame.width(), frame.height()}));
    if (!a.dump.empty()) {
      nlohmann::json j = dump_arrangement(frame);
      j["scene"] = a.scene;
      io::write_atomically(a.dump, [&](const fs::path& tmp) {
        std::ofstream out(tmp);
        out << j.dump() << "\n";
        if (!out.flush()) throw std::runtime_error(a.dump + ": write failed");
      });
    }
    if (pick) print_pick(describe_point(frame, *pick));
    return;
  }
  if (area.width == 0) area = default_area(frame.width(), frame.height());
  run_window(source, std::move(frame), layers, area, fs::path(a.scene).filename().string(),
             !a.no_opengl);
}

}  // namespace
}  // namespace wisp::inspect

int main(int argc, char** argv) {
  wisp::inspect::Args a;
  CLI::App app{"wisp-inspect: look inside a frame of a scene (layers, picking, snapshots)"};
  app.add_option("scene", a.scene, "Scene file (.json)")->required();
  app.add_option("--frame", a.frame, "Frame to show (default 0)");
  app.add_option("--anim", a.anim, "Use this saved animation (.wsim) instead of simulating");
  app.add_option("--size", a.size, "Image size WxH (default: the scene camera's)");
  app.add_option("--layers", a.layers,
                 "Layers to show, comma-separated (default image): image, faces, coverage, mask, "
                 "constraints, residual, outlines, visibility, curves, vertices, ink");
  app.add_option("--residual-step", a.residual_step,
                 "Solver step the residual layer shows (0: after the FMG start; default: last)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--snapshot", a.snapshot, "Draw the layers of the frame to this PNG, no window");
  app.add_option("--dump", a.dump, "Write the frame's arrangement to this JSON file, no window");
  app.add_option("--pick", a.pick, "Describe the point X,Y (frame pixels) on stdout, no window");
  app.add_option("--window", a.window, "Size WxH of the window's frame area (default: fit 800)");
  app.add_flag_callback(
      "--help-keys",
      [] {
        for (const std::string& l : wisp::inspect::help_lines({})) std::printf("%s\n", l.c_str());
        throw CLI::Success();
      },
      "Print the window's keys and mouse actions, and exit");
  app.add_flag("--no-opengl", a.no_opengl,
               "Plain window instead of OpenGL (its own wheel zoom then adds to ours)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return wisp::cli::report_parse_error(app, e, "wisp-inspect");
  }
  try {
    wisp::inspect::run(a);
  } catch (const std::exception& e) {
    return wisp::cli::report_error("wisp-inspect", e.what());
  }
  return 0;
}
