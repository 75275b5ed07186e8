// Exact and textbook solvers of the same discrete Problem, built on Eigen's sparse solvers. They
// are the references of the accuracy tests and the peers of the solver benchmark: the system is
// assembled from the Problem exactly as the multigrid sees it (free pixels that no fixed or
// anchored pixel reaches are set to 0 in both).
#pragma once

#include <vector>

#include "diffusion/problem.hpp"

namespace wisp::diffusion {

enum class ReferenceMethod {
  SimplicialLDLT,     // sparse Cholesky: the exact discrete solution
  ConjugateGradient,  // Eigen CG with its default (Jacobi) preconditioner
};

struct ReferenceResult {
  std::vector<float> planes;  // channels planes of W*H
  double seconds = 0;         // assembly + factorisation/iteration, all channels
  int iterations = 0;         // CG: the largest over channels
};

// `tolerance` is the relative residual for CG (ignored by LDLT).
ReferenceResult solve_reference(const Problem& problem, ReferenceMethod method,
                                double tolerance = 1e-5);

}  // namespace wisp::diffusion
