// Spatially varying Gaussian blur by interpolation between a ladder of blurs, and the blur map
// solved alone (see blur.hpp).
#include "diffusion/blur.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "diffusion/rasterize.hpp"

namespace wisp::diffusion {
namespace {

// `src` blurred by a Gaussian of sigma s: directly, or on a reduced image (blur.hpp) when s is
// at least `pyramid_from`.
cv::Mat rung(const cv::Mat& src, float s, float pyramid_from) {
  cv::Mat out;
  int f = 1;
  while (s >= pyramid_from && s / (2 * f) >= 2) f *= 2;
  if (f == 1) {
    cv::GaussianBlur(src, out, cv::Size(0, 0), s, s, cv::BORDER_REFLECT);
    return out;
  }
  const double sigma_small = std::sqrt(double(s) * s / (double(f) * f) - 0.25);
  cv::Mat small;
  cv::resize(src, small, cv::Size((src.cols + f - 1) / f, (src.rows + f - 1) / f), 0, 0,
             cv::INTER_AREA);
  cv::GaussianBlur(small, small, cv::Size(0, 0), sigma_small, sigma_small, cv::BORDER_REFLECT);
  cv::resize(small, out, src.size(), 0, 0, cv::INTER_LINEAR);
  return out;
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

  std::vector<float> out(planes.size());
  for (int c = 0; c < channels; ++c) {
    const cv::Mat src(height, width, CV_32F, const_cast<float*>(&planes[c * n]));
    std::vector<cv::Mat> ladder(rungs.size());
    ladder[0] = src;
    for (size_t k = 1; k < rungs.size(); ++k) ladder[k] = rung(src, rungs[k], options.pyramid_from);
    float* dst = &out[c * n];
    for (size_t i = 0; i < n; ++i) {
      const float s = std::clamp(sigma[i], 0.0f, rungs.back());
      size_t k = 0;
      while (k + 2 < rungs.size() && rungs[k + 1] < s) ++k;
      const float f = (s - rungs[k]) / (rungs[k + 1] - rungs[k]);
      dst[i] = (1 - f) * ladder[k].ptr<float>()[i] + f * ladder[k + 1].ptr<float>()[i];
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
