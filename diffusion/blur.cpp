// Spatially varying Gaussian blur by interpolation between a ladder of blurs (see blur.hpp).
#include "diffusion/blur.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace wisp::diffusion {

std::vector<float> spatially_varying_blur(const std::vector<float>& planes, int channels, int width,
                                          int height, const std::vector<float>& sigma) {
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
    for (size_t k = 1; k < rungs.size(); ++k)
      cv::GaussianBlur(src, ladder[k], cv::Size(0, 0), rungs[k], rungs[k], cv::BORDER_REFLECT);
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

}  // namespace wisp::diffusion
