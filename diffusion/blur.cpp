// Spatially varying Gaussian blur by interpolation between a ladder of blurs (each rung made by
// the blur module, blur_module.hpp), and the blur map solved alone (see blur.hpp).
#include "diffusion/blur.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "diffusion/blur_module.hpp"
#include "diffusion/rasterize.hpp"
#include "util/module.hpp"

namespace wisp::diffusion {
namespace {

using RungFunction = decltype(&wisp_blur_rung);

// The blur module, loaded once per process on first use (util/module.hpp). Throws when it is
// missing or from another build.
RungFunction blur_rung() {
  static const std::pair<RungFunction, std::string> loaded = [] {
    util::Module module = util::open_module("wisp-blur.so", "blur");
    const auto rung = module.function<RungFunction>("wisp_blur_rung");
    return std::make_pair(rung, module.error);
  }();
  if (!loaded.first) throw std::runtime_error(loaded.second);
  return loaded.first;
}

}  // namespace

std::vector<float> spatially_varying_blur(const std::vector<float>& planes, int channels, int width,
                                          int height, const std::vector<float>& sigma,
                                          const BlurOptions& options) {
  const size_t n = size_t(width) * size_t(height);
  const float largest = sigma.empty() ? 0.0f : *std::max_element(sigma.begin(), sigma.end());
  if (!(largest > 0.0f)) return planes;
  std::vector<float> rungs = {0.0f, 0.5f};
  while (rungs.back() < largest) rungs.push_back(rungs.back() * 2);

  const RungFunction rung = blur_rung();
  std::vector<float> out(planes.size());
  std::vector<std::vector<float>> blurred(rungs.size() - 1, std::vector<float>(n));
  for (int c = 0; c < channels; ++c) {
    const float* src = &planes[c * n];
    std::vector<const float*> ladder = {src};
    for (size_t k = 1; k < rungs.size(); ++k) {
      if (!rung(src, width, height, rungs[k], options.pyramid_from, blurred[k - 1].data()))
        throw std::runtime_error("blur: OpenCV could not blur a " + std::to_string(width) + "x" +
                                 std::to_string(height) + " image");
      ladder.push_back(blurred[k - 1].data());
    }
    float* dst = &out[c * n];
    for (size_t i = 0; i < n; ++i) {
      const float s = std::clamp(sigma[i], 0.0f, rungs.back());
      size_t k = 0;
      while (k + 2 < rungs.size() && rungs[k + 1] < s) ++k;
      const float f = (s - rungs[k]) / (rungs[k + 1] - rungs[k]);
      dst[i] = (1 - f) * ladder[k][i] + f * ladder[k + 1][i];
    }
  }
  return out;
}

Solution solve_blur_map(const std::vector<DiffusionCurve>& curves, int width, int height,
                        const SolverOptions& solver, const std::vector<float>* warm_start) {
  RasterizeOptions options;
  options.blur_only = true;
  const Problem problem = rasterize(curves, width, height, options);
  const bool warm = warm_start && warm_start->size() == problem.pixel_count();
  return solve_multigrid(problem, solver, warm ? warm_start : nullptr);
}

}  // namespace wisp::diffusion
