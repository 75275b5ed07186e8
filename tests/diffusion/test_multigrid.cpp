// Accuracy and convergence of the multigrid solver against exact answers.
#include <catch2/catch.hpp>

#include "diffusion/multigrid.hpp"
#include "diffusion/rasterize.hpp"
#include "diffusion/reference.hpp"
#include "scenes.hpp"

using namespace wisp::diffusion;

namespace {

float max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
  REQUIRE(a.size() == b.size());
  float m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

Problem random_layout(int size, unsigned seed, int curves, bool neumann) {
  std::mt19937 rng(seed);
  std::vector<DiffusionCurve> cs;
  for (int i = 0; i < curves; ++i) {
    cs.push_back(wisp::test::random_curve(rng, size, 3));
    if (neumann && i % 3 == 0) cs.back().right_boundary = Boundary::Neumann;
  }
  return rasterize(cs, size, size);
}

}  // namespace

TEST_CASE("multigrid matches the exact discrete solution on random curve layouts",
          "[multigrid]") {
  for (int size : {64, 128, 256}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      const Problem p = random_layout(size, seed * 7 + size, 6, seed == 3);
      SolverOptions opt;
      opt.tolerance = 1e-6;
      const Solution mg = solve_multigrid(p, opt);
      const ReferenceResult exact = solve_reference(p, ReferenceMethod::SimplicialLDLT);
      INFO("size " << size << " seed " << seed << " cycles " << mg.stats.cycles << " residual "
                   << mg.stats.final_residual);
      CHECK(max_abs_difference(mg.planes, exact.planes) <= 1e-4f);
    }
  }
}
