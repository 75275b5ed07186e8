// Reblur (Orzan et al. 2008, section 3.3): each curve carries blur values along its length; they
// are diffused like colours into a blur map sigma(x), and the solved image is then blurred with a
// Gaussian whose standard deviation varies per pixel.
//
// Method. The image is blurred at a ladder of sigmas (0, 0.5, 1, 2, 4, ...: each twice the last,
// up to the largest value in the map); every pixel interpolates linearly between the two rungs
// that bracket its own sigma. A Gaussian of sigma s lies between those of its rungs, so the
// result is within a rung's difference of the exact spatially varying blur, and exact where the
// map sits on a rung (in particular 0: sharp pixels stay exactly as solved).
//
// Pyramid rungs (BlurOptions::pyramid_from). A rung of sigma s costs O(s) per pixel at full
// resolution. From `pyramid_from` on, a rung is made on the image box-averaged by a factor f (a
// power of two with s/f in [2, 4)), blurred there by sigma' and read back bilinearly: the box
// (variance f^2/12), the blur (f^2 sigma'^2) and the bilinear tent (f^2/6) add up to s^2, so the
// rung is a Gaussian of sigma s up to the shape of those two small kernels, at O(1) per pixel.
#pragma once

#include <cmath>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "diffusion/multigrid.hpp"

namespace wisp::diffusion {

struct BlurOptions {
  float pyramid_from = INFINITY;  // rungs of at least this sigma (px) on a reduced image
};

// `planes`: `channels` planes of width*height; `sigma`: width*height standard deviations in
// pixels (negative values count as 0). Returns the blurred planes. Borders reflect.
std::vector<float> spatially_varying_blur(const std::vector<float>& planes, int channels, int width,
                                          int height, const std::vector<float>& sigma,
                                          const BlurOptions& options = {});

// The blur map alone: the curves' blur stops diffused over a width x height image like a colour
// (one channel, RasterizeOptions::blur_only): every curve cuts the links it crosses and holds its
// blur on both sides, where it is active. Colours and gradient curves play no part.
// `warm_start`: a previous map of the same size, or null.
Solution solve_blur_map(const std::vector<DiffusionCurve>& curves, int width, int height,
                        const SolverOptions& solver = {},
                        const std::vector<float>* warm_start = nullptr);

}  // namespace wisp::diffusion
