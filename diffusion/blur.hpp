// Reblur (Orzan et al. 2008, section 3.3): each curve carries blur values along its length; they
// are diffused like colours into a blur map sigma(x), and the solved image is then blurred with a
// Gaussian whose standard deviation varies per pixel.
//
// Method. The image is blurred at a ladder of sigmas (0, 0.5, 1, 2, 4, ...: each twice the last,
// up to the largest value in the map); every pixel interpolates linearly between the two rungs
// that bracket its own sigma. A Gaussian of sigma s lies between those of its rungs, so the
// result is within a rung's difference of the exact spatially varying blur, and exact where the
// map sits on a rung (in particular 0: sharp pixels stay exactly as solved).
#pragma once

#include <vector>

namespace wisp::diffusion {

// `planes`: `channels` planes of width*height; `sigma`: width*height standard deviations in
// pixels (negative values count as 0). Returns the blurred planes. Borders reflect.
std::vector<float> spatially_varying_blur(const std::vector<float>& planes, int channels, int width,
                                          int height, const std::vector<float>& sigma);

}  // namespace wisp::diffusion
