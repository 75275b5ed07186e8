// The boundary between diffusion/blur.cpp and the blur module, wisp-blur.so: one rung of the blur
// ladder (blur.hpp), made with OpenCV's Gaussian blur and resampling, as a plain C function.
// OpenCV and the libraries it loads (X11, GL, LAPACK) are half of a command's start-up, and only
// a drawing with blur needs them, so the module is loaded (dlopen) the first time a picture is
// blurred, not by every program that links the diffusion stage (docs/performance.md). It is
// built from diffusion/blur_module.cpp alone and lives in lib/wisp/ beside the bin/ folder of
// the executables, where util/module.hpp finds every module.
#pragma once

extern "C" {

// `src` (width x height floats, rows without padding) blurred by a Gaussian of standard deviation
// `sigma` pixels into `out` (same layout), borders reflected: directly, or on an image reduced by
// a power of two when sigma >= pyramid_from (blur.hpp). 1 on success, 0 when OpenCV failed.
int wisp_blur_rung(const float* src, int width, int height, float sigma, float pyramid_from,
                   float* out);

}  // extern "C"
