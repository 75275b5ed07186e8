// Eigen reference solvers of the discrete problem (see reference.hpp).
#include "diffusion/reference.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "diffusion/timer.hpp"

namespace wisp::diffusion {

ReferenceResult solve_reference(const Problem& p, ReferenceMethod method, double tolerance) {
  check_problem(p);
  const auto t0 = Clock::now();
  const int W = p.width, H = p.height;
  const size_t n = p.pixel_count();

  // Free pixels reached from a fixed or anchored pixel get an unknown; the others are set to 0.
  std::vector<int> unknown(n, -1);
  const std::vector<std::uint8_t> reached = reached_from_fixed(p);
  int m = 0;
  for (size_t i = 0; i < n; ++i)
    if (!p.fixed[i] && reached[i]) unknown[i] = m++;

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(size_t(m) * 5);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(m, p.channels);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = p.index(x, y);
      const int r = unknown[i];
      if (r < 0) continue;
      const bool open[4] = {
          x + 1 < W && (p.links[i] & kOpenEast) != 0, x > 0 && (p.links[i - 1] & kOpenEast) != 0,
          y + 1 < H && (p.links[i] & kOpenSouth) != 0, y > 0 && (p.links[i - W] & kOpenSouth) != 0};
      const size_t nb[4] = {i + 1, i - 1, i + W, i - W};
      int degree = 0;
      for (int k = 0; k < 4; ++k) {
        if (!open[k]) continue;
        ++degree;
        if (unknown[nb[k]] >= 0)
          triplets.emplace_back(r, unknown[nb[k]], -1.0);
        else if (p.fixed[nb[k]])
          for (int c = 0; c < p.channels; ++c) b(r, c) += p.value[c * n + nb[k]];
      }
      const double w = p.anchor_weight[i];  // a link to the anchor value (problem.hpp)
      if (w > 0)
        for (int c = 0; c < p.channels; ++c) b(r, c) += w * p.value[c * n + i];
      triplets.emplace_back(r, r, degree + w);
      if (!p.rhs.empty())
        for (int c = 0; c < p.channels; ++c) b(r, c) -= p.rhs[c * n + i];
    }
  Eigen::SparseMatrix<double> A(m, m);
  A.setFromTriplets(triplets.begin(), triplets.end());

  ReferenceResult out;
  Eigen::MatrixXd x(m, p.channels);
  if (m > 0) {
    if (method == ReferenceMethod::SimplicialLDLT) {
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
      if (ldlt.info() != Eigen::Success)
        throw std::runtime_error("reference solver: LDLT factorisation failed");
      x = ldlt.solve(b);
    } else {
      Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg(A);
      cg.setTolerance(tolerance);
      cg.setMaxIterations(100000);
      for (int c = 0; c < p.channels; ++c) {
        x.col(c) = cg.solve(b.col(c));
        out.iterations = std::max(out.iterations, int(cg.iterations()));
      }
    }
  }
  out.planes.assign(n * p.channels, 0.0f);
  for (int c = 0; c < p.channels; ++c)
    for (size_t i = 0; i < n; ++i)
      out.planes[c * n + i] =
          unknown[i] >= 0 ? float(x(unknown[i], c)) : (p.fixed[i] ? p.value[c * n + i] : 0.0f);
  out.seconds = seconds_since(t0);
  return out;
}

}  // namespace wisp::diffusion
