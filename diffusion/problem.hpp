// The discrete diffusion problem on a W x H pixel grid, as the rasterizer produces it and the
// solvers consume it. Pixels are unknowns coupled to their 4 neighbours by links; a link may be
// cut (a curve crosses it: colour must not flow through). Curves hold their colours in two ways:
//  - a pixel may be anchored: curves cross some of its links at distance theta_k (in link
//    lengths) with colour c_k facing it. Each crossing acts as a neighbour at distance theta_k
//    holding c_k (the Shortley-Weller ghost point), which sums to an anchor weight
//    w_p = sum 1/theta_k and an anchor value a_p = (sum c_k / theta_k) / w_p;
//  - a pixel may be fixed (Dirichlet: it holds a value). The rasterizer fixes a pixel whose centre
//    a curve almost touches, where 1/theta would be huge, and in its first-order mode every
//    pixel next to a curve.
// The solution u satisfies, at every pixel p that is not fixed,
//
//     sum over open links (p,q) of (u_q - u_p) + w_p (a_p - u_p) = g_p
//
// (with w_p = 0 away from curves: the 5-point Laplacian, L u = g), where g = 0 for diffusion
// curves (Laplace) or g = div w for a gradient field w (Poisson, Orzan et al. 2008). The operator
// is symmetric, and an anchor is exactly an open link to a fixed neighbour when theta = 1. Links
// leaving the image do not exist, which is a Neumann condition at the border.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace wisp::diffusion {

// Link bits of Problem::links.
constexpr std::uint8_t kOpenEast = 1;   // the link (i,j)-(i+1,j) is open
constexpr std::uint8_t kOpenSouth = 2;  // the link (i,j)-(i,j+1) is open

struct Problem {
  int width = 0;
  int height = 0;
  int channels = 3;  // 3 (RGB) or 4 (RGB + blur sigma, diffused like a colour)

  std::vector<std::uint8_t> fixed;   // W*H: 1 where the pixel is a Dirichlet pixel
  std::vector<std::uint8_t> links;   // W*H: kOpenEast | kOpenSouth bits
  std::vector<float> anchor_weight;  // W*H: w_p (see above); 0 on fixed pixels and away from curves
  // channels planes of W*H (plane c at c*W*H): the value of fixed pixels, the anchor value a_p of
  // anchored ones, 0 elsewhere.
  std::vector<float> value;
  // Empty for Laplace; otherwise channels planes of W*H holding g (see above).
  std::vector<float> rhs;

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

// An empty problem: all pixels free and unanchored, all links inside the image open, no
// right-hand side.
Problem make_open_problem(int width, int height, int channels);

// Adds the divergence of a link gradient field to the right-hand side: wx holds, per channel
// plane, the wanted difference u(i+1,j) - u(i,j) on each east link, wy the difference
// u(i,j+1) - u(i,j) on each south link. Only open links contribute, so a field that is the exact
// difference of some image makes that image a solution.
void add_gradient_field(Problem& problem, const std::vector<float>& wx,
                        const std::vector<float>& wy);

// 1 for every pixel that is fixed or anchored, or connected through open links to such a pixel.
// The others lie in regions sealed off by barriers without any colour: their value is undefined.
std::vector<std::uint8_t> reached_from_fixed(const Problem& problem);

// Throws std::invalid_argument when the sizes or array lengths are inconsistent, a value is not
// finite, or an anchor weight is negative or sits on a fixed pixel.
void check_problem(const Problem& problem);

}  // namespace wisp::diffusion
