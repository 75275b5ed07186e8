// The inspector's layers and how each is drawn: a pure function from a frame, the set of layers
// turned on and a view transform (zoom and pan) to an image. The window and `--snapshot` both
// call it, so what the tests check is what a researcher sees.
//
// Layers come in two kinds. Area layers fill pixels: the finished image, the arrangement's faces,
// the coverage count, the hair mask, the constraint pixels of the solve and the solver residual.
// The lowest area layer turned on is drawn opaque, each one above it at kStackedOpacity, so two
// of them can be compared in place. Line layers (outlines, visible and hidden pieces, centre
// curves, intersection vertices, ink) are drawn on top, anti-aliased, with widths in screen
// pixels, so they stay thin when zoomed in; vector fills are redrawn at the zoomed resolution,
// pixel rasters (image, mask, constraints, residual) are magnified without smoothing, so single
// pixels stay visible. The fills of faces and coverage are not anti-aliased: a canvas pixel
// takes the colour of the face that contains its centre (sampled exactly, not by Cairo), which
// keeps colours exact.
#pragma once

#include <Eigen/Core>
#include <array>
#include <bitset>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "apps/inspect/inspected_frame.hpp"

namespace wisp::inspect {

enum class Layer : int {
  Image,        // the finished frame
  Faces,        // covered arrangement faces, coloured by their front-most wisp
  Coverage,     // number of wisps covering each face (heat map)
  Mask,         // the anti-aliased hair mask (white hair on black)
  Constraints,  // fixed and anchored pixels in their values (cut links too when zoomed in)
  Residual,     // |b - A u| after a solver step, log scale
  Outlines,     // wisp outlines coloured by wisp id
  Visibility,   // visible (green) and hidden (red) outline pieces, depth seams (violet)
  Curves,       // centre curves with their Bezier control points
  Vertices,     // intersection vertices of the arrangement
  Ink,          // ink strokes (the silhouette and occlusion lines when the style has none)
};
constexpr int kLayerCount = 11;

struct LayerInfo {
  Layer layer;
  const char* name;   // as in --layers
  char key;           // toggles the layer in the window
  bool area;          // an area layer (see above)
  const char* title;  // one line for the help overlay
};

// Every layer, in drawing order (bottom to top).
const std::array<LayerInfo, kLayerCount>& layer_table();
const LayerInfo& layer_info(Layer layer);

// "faces,curves" -> the layers. Throws std::invalid_argument naming the unknown layer and the
// known ones, or an empty list.
std::vector<Layer> parse_layers(const std::string& list);

struct LayerSet {
  std::bitset<kLayerCount> on;
  int residual_step = -1;  // solver step the residual layer shows; -1: the last

  bool has(Layer l) const { return on[size_t(l)]; }
  void set(Layer l, bool value = true) { on[size_t(l)] = value; }
  void toggle(Layer l) { on.flip(size_t(l)); }
};

// Frame pixels to canvas pixels: canvas = frame * zoom + offset.
struct ViewTransform {
  double zoom = 1;
  Eigen::Vector2d offset{0, 0};

  Eigen::Vector2d to_canvas(const Eigen::Vector2d& p) const { return p * zoom + offset; }
  Eigen::Vector2d to_frame(const Eigen::Vector2d& q) const { return (q - offset) / zoom; }
};

// The layers of `frame` that `layers` turns on, on a canvas of `canvas` pixels: an 8-bit BGR
// image (CV_8UC3). Uncovered canvas shows kBackground.
cv::Mat draw_layers(const InspectFrame& frame, const LayerSet& layers, const ViewTransform& view,
                    cv::Size canvas);

// The solver step the residual layer shows for `layers` (clamped), or -1 without a solve.
int residual_step(const InspectFrame& frame, const LayerSet& layers);

// Colours, RGB. Exposed for the legend, the docs and the tests.
using Rgb8 = std::array<std::uint8_t, 3>;
constexpr Rgb8 kBackground{40, 40, 40};
constexpr double kStackedOpacity = 0.6;
constexpr Rgb8 kVisibleColor{70, 230, 90};
constexpr Rgb8 kHiddenColor{235, 50, 50};
constexpr Rgb8 kSeamColor{190, 90, 255};  // depth seams: where two wisps swap depth order
constexpr Rgb8 kCurveColor{235, 235, 235};
constexpr Rgb8 kControlPolygonColor{130, 130, 130};
constexpr Rgb8 kHandleColor{60, 200, 255};
constexpr Rgb8 kOnCurveColor{255, 230, 0};
constexpr Rgb8 kVertexColor{255, 150, 0};
constexpr Rgb8 kSilhouetteColor{255, 255, 255};
constexpr Rgb8 kOcclusionColor{255, 70, 210};
constexpr Rgb8 kCutLinkColor{200, 200, 200};
// Residual colour scale: log10 |r| from kResidualLog10Min (dark) to kResidualLog10Max (bright);
// an exact 0 (fixed pixels) is not drawn.
constexpr double kResidualLog10Min = -8, kResidualLog10Max = -2;

// A wisp's own colour: hues spread by the golden ratio, so neighbouring ids differ.
Rgb8 wisp_color(int wisp);
// Covered face number `number` (its rank among the covered faces inside the view, in the view's
// face order) with front-most wisp `front`: the front wisp's hue in the top 3 bits of each
// channel and the face number in the low kFaceCodeBits bits of each channel, so up to
// kFaceCodes covered faces get pairwise distinct colours (beyond that numbers repeat), and
// neighbouring faces of one wisp differ slightly in shade. Never grey.
constexpr int kFaceCodeBits = 5;
constexpr int kFaceCodes = 1 << (3 * kFaceCodeBits);
Rgb8 face_color(int front, int number);
// Coverage count 1, 2, ... (kCoverageLevels and more share the last colour); 0 is not drawn.
constexpr int kCoverageLevels = 16;
Rgb8 coverage_color(int count);
// The residual scale's colour for |r| > 0.
Rgb8 residual_color(float residual);

}  // namespace wisp::inspect
