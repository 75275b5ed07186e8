// The inspector window's state and behaviour, without the window: which frame and layers are
// shown, zoom and pan, the frame prompt, the last pick; how keys and mouse events change that
// state; and the window's picture (the layers of the frame area, a side panel with the frame's
// numbers, legends and the pick, and the help overlay). inspect_main.cpp only forwards highgui
// events here and shows the result, so all of this can be exercised without a display.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/inspect/inspected_frame.hpp"
#include "apps/inspect/layers.hpp"

namespace wisp::inspect {

constexpr int kPanelWidth = 400;       // side panel, canvas pixels
constexpr int kMinCanvasHeight = 680;  // room for the panel's text

struct WindowState {
  int frame = 0;
  int frame_count = 1;
  int frame_width = 0, frame_height = 0;  // of the frames (pixels)
  cv::Size area;                          // the frame area of the window (canvas pixels)
  LayerSet layers;
  int residual_steps = 0;  // solver steps recorded for the shown frame
  ViewTransform view;
  bool help = false;
  bool prompting = false;  // typing a frame number after 'g'
  std::string prompt;
  std::optional<Eigen::Vector2d> pick_point;  // frame pixels
  std::vector<std::string> pick;              // its description
  std::string message;                        // last action, shown in the panel
  // Mouse: where the left button went down, and whether it has moved far enough to pan.
  std::optional<Eigen::Vector2d> press;
  bool dragging = false;
};

// What the window must do after an event.
enum class Action { None, Redraw, LoadFrame, Pick, Save, Quit };

// A state showing `first_frame` of `frame_count` frames of width x height pixels in a frame
// area of `area` (fitted), with `layers` on.
WindowState initial_state(int first_frame, int frame_count, int width, int height, cv::Size area,
                          const LayerSet& layers);

// The view that fits the whole frame in the frame area, centred.
ViewTransform fit_view(cv::Size area, int width, int height);

// The default frame area: the frame scaled to fit `max_side` x `max_side` (up or down).
cv::Size default_area(int width, int height, int max_side = 800);

// Keys as cv::waitKeyEx returns them (X11 keysyms for arrows and paging keys).
Action handle_key(WindowState& state, int key);

// Mouse events as highgui reports them (cv::MouseEventTypes, canvas coordinates, flags). A
// left click without movement is a pick (Action::Pick, state.pick_point set); a left drag
// pans; the wheel zooms about the pointer.
Action handle_mouse(WindowState& state, int event, int x, int y, int flags);

// The window's picture: the frame area (draw_layers under state.view), the side panel, and the
// help overlay when state.help is on.
cv::Mat compose_window(const InspectFrame& frame, const WindowState& state,
                       const std::string& title);

// The help text, one line per entry (also printed by --help-keys and listed in docs/inspect.md).
std::vector<std::string> help_lines(const LayerSet& layers);

}  // namespace wisp::inspect
