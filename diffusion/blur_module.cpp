// The blur module (blur_module.hpp): one rung of the blur ladder with OpenCV.
#include "diffusion/blur_module.hpp"

#include <cmath>
#include <exception>
#include <opencv2/imgproc.hpp>

namespace {

// `src` blurred by a Gaussian of sigma s into `out` (of src's size and type, so OpenCV writes
// into its buffer): directly, or on a reduced image (blur.hpp) when s is at least `pyramid_from`.
void rung(const cv::Mat& src, float s, float pyramid_from, cv::Mat& out) {
  int f = 1;
  while (s >= pyramid_from && s / (2 * f) >= 2) f *= 2;
  if (f == 1) {
    cv::GaussianBlur(src, out, cv::Size(0, 0), s, s, cv::BORDER_REFLECT);
    return;
  }
  const double sigma_small = std::sqrt(double(s) * s / (double(f) * f) - 0.25);
  cv::Mat small;
  cv::resize(src, small, cv::Size((src.cols + f - 1) / f, (src.rows + f - 1) / f), 0, 0,
             cv::INTER_AREA);
  cv::GaussianBlur(small, small, cv::Size(0, 0), sigma_small, sigma_small, cv::BORDER_REFLECT);
  cv::resize(small, out, src.size(), 0, 0, cv::INTER_LINEAR);
}

}  // namespace

extern "C" int wisp_blur_rung(const float* src, int width, int height, float sigma,
                              float pyramid_from, float* out) {
  try {
    const cv::Mat in(height, width, CV_32F, const_cast<float*>(src));
    cv::Mat dst(height, width, CV_32F, out);
    rung(in, sigma, pyramid_from, dst);
    return dst.data == reinterpret_cast<unsigned char*>(out);  // 0 if OpenCV reallocated it
  } catch (const std::exception&) {  // cv::Exception, std::bad_alloc: not across the C boundary
    return 0;
  }
}
