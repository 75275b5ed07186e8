// The frames of an animation as one animated SVG (animation.svg): every frame's SVG
// (picture_svg.cpp, either style) in one document, shown in turn at the frame rate and looping,
// by SMIL alone (no script), so a browser plays it when it opens the file.
//
// Layout. The frames' Inkscape layers stay layers of the document (background, body, hair base,
// hair, highlights, ink, and whatever layers the frames have), so an editor hides one layer for
// the whole animation. Inside a layer, each run of consecutive frames whose content is the same
// becomes one group, shown over that run's time by a discrete <animate> of `display` (values
// "none;inline;none" at keyTimes first/N, last/N): a layer that never changes (the background)
// is one static group, a still head is one group for as long as it stays still. The group holding
// frame 0 is displayed and the others carry display="none", so viewers without animation
// (librsvg, thumbnails, print) show the first frame. Content repeated in groups that are not
// neighbours (an element written the same way in two runs, or a gradient or clip path defined the
// same in two frames) is written once, in <defs>, and each place uses it (<use>, url(#id)).
// Coordinates stay as the frames wrote them (svg_decimals). Ids get the frame they come from:
// `wisp-17-f12`. Hidden layers of the frames (the debug wisp outlines) are left out.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace wisp::render {

struct SvgAnimationStats {
  int frames = 0;
  int groups = 0;  // frame groups written, over all layers (one per run of equal frames)
  int shared = 0;  // elements and definitions written once and referenced more than once
  std::size_t bytes = 0;
};

// The animated document of `frames` (the frames' SVG texts, in order; names for messages) at
// `fps` frames per second. Throws std::runtime_error naming the frame that is not one of our
// frame SVGs, or whose size differs from the first's.
std::string animate_svg_frames(const std::vector<std::string>& frames,
                               const std::vector<std::string>& names, double fps,
                               SvgAnimationStats* stats = nullptr);

// The frame files' animation written to `path` (a temporary name, then renamed).
SvgAnimationStats write_svg_animation(const std::vector<std::filesystem::path>& frames, double fps,
                                      const std::filesystem::path& path);

}  // namespace wisp::render
