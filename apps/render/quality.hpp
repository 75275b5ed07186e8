// How well a frame holds up at full size: the frame rendered at size S against the same frame
// rendered at 4S and box-filtered down to S (each S pixel the mean of its 4 x 4 block), compared
// inside the figure (every pixel that is not plain background in either image). A renderer whose
// curves, hairline and body edges are right at 1:1 differs from its own supersampled picture only
// by the discretisation of smooth shading; staircases, seams and misplaced edges show up as large
// per-pixel errors. Used by `wisp-bench quality` and the tests.
#pragma once

#include <Eigen/Core>
#include <filesystem>

namespace wisp::render {

struct FrameQuality {
  long figure_pixels = 0;  // pixels compared
  double p99 = 0;          // 99th percentile of the per-pixel error, 0-255 (max over RGB)
  double over_32 = 0;      // fraction of figure pixels whose error exceeds 32/255
  double mean = 0;         // mean per-pixel error, 0-255
};

// `frame`: an S x S (or W x H) PNG; `reference`: the same frame at an integer multiple of that
// size. `background`: the scene's background colour in [0,1]. Throws std::runtime_error naming
// the file when an image cannot be read or the sizes are not multiples.
FrameQuality frame_quality(const std::filesystem::path& frame,
                           const std::filesystem::path& reference,
                           const Eigen::Vector3f& background);

}  // namespace wisp::render
