// Geometric multigrid for the constrained 5-point problem of problem.hpp, all channels at once,
// in float32.
//
// Formulation. With u0 the initial guess (fixed pixels hold their colours), the solver computes
// the residual r0 = b - A u0 once and then solves the correction equation A e = r0 on the free
// pixels only (e = 0 on fixed pixels), A being the negative Laplacian over open links plus the
// anchor weights on the diagonal (problem.hpp): symmetric positive definite on each region that
// a fixed or anchored pixel reaches.
//
// Coarse levels (Dendy's black-box multigrid, "Black box multigrid", J. Comput. Phys. 48, 1982):
// vertex-centred standard coarsening (coarse point (I,J) sits on fine pixel (2I,2J)), an
// operator-dependent prolongation P built from each fine pixel's own stencil, restriction P^T,
// and Galerkin coarse operators A_c = P^T A P (9-point stencils). P never interpolates across a
// cut link and is zero on fixed pixels, and anchors enter the Galerkin products through the
// finest diagonal, so coarse levels keep the meaning of the constraints: a barrier stays a
// barrier and a Dirichlet curve still pins the correction on every level, however thin it is.
// A coarse point whose fine pixel is fixed is itself fixed.
//
// Cycle. Full multigrid (FMG) start, then V(0,2) cycles on the finest level (its last
// post-smoothing left it smoothed, and restricted the residual it measured: the next cycle starts
// at the coarse correction), V(2,2) on level 1 and V(4,4) on levels 2 and coarser, which are
// cheap (SolverOptions::coarse_smooth), until the relative residual ||b - A u|| / ||b|| of every
// channel is below the tolerance, or, with SolverOptions::max_error, until the estimated largest
// error is below that bound (accelerated by conjugate gradients, with symmetric V(2,2) cycles as
// their preconditioner, when they slow down, see SolverOptions::krylov; refined in double
// precision when the tolerance is below what float32 reaches). The finest level's residual is
// taken from differences of neighbouring values, which float32 holds exactly where the answer is
// smooth, so that the cycles converge past the rounding of the answer's own size. Smoothing is
// Gauss-Seidel in an order-independent colouring: red-black on the 5-point finest level, four
// colours on the 9-point coarse levels; rows are processed in parallel (TBB) and every reduction
// sums in a fixed order, so the result does not depend on the number of threads. The coarsest level
// (<= 64 points) is solved exactly with a dense LDLT.
//
// Pixels in a region that no fixed or anchored pixel reaches (sealed by Neumann barriers) have no
// defined value; they are reported in the statistics and set to 0.
#pragma once

#include <functional>
#include <vector>

#include "diffusion/problem.hpp"

namespace wisp::diffusion {

// The largest error that an 8-bit image cannot show: a quarter of a step of 1/255, so rounding
// to 8 bits moves a pixel by at most one step from where the exact discrete answer rounds.
constexpr double kEightBitError = 0.25 / 255;

struct SolverOptions {
  double tolerance = 1e-5;  // relative residual per channel
  // When > 0, the stopping rule is this bound on the error instead: the solve stops as soon as
  // the estimated largest difference |u - u_exact| from the exact discrete answer, over every
  // pixel and channel, is below it (tolerance is then not used). The estimate after a cycle that
  // changed u by at most delta and reduced the residual by rho is delta * rho / (1 - rho) (the
  // remaining error if later cycles kept that rate), times a safety factor; see multigrid.cpp.
  // kEightBitError stops at what an 8-bit image can show (tested against Eigen's LDLT).
  double max_error = 0;
  int max_cycles = 100;  // V-cycles (or CG iterations) after the FMG start
  // Sweeps before and after the coarse correction on levels 0 and 1. The finest level is
  // pre-smoothed only in full multigrid's visit and in conjugate gradients' preconditioner: the
  // solve's other cycles start it at the coarse correction (see the file's comment).
  int pre_smooth = 2;
  int post_smooth = 2;
  // Sweeps before and after the coarse correction on levels 2 and coarser. They hold at most a
  // sixteenth of the finest points, so 4 cost about 4 % of a cycle more than 2, and bring their
  // correction closer to an exact coarse solve: the smooth modes that only the coarsest grids
  // see (nearly sealed pockets, long corridors) then fall faster, and the stopping rule holds a
  // cycle or more sooner on such drawings (docs/diffusion.md, "Solver").
  int coarse_smooth = 4;
  bool full_multigrid = true;
  // Plain V-cycles converge at the model-problem rate on ordinary drawings. Where barriers nearly
  // seal off a region, a few modes escape the coarse grids and the cycles slow down; as soon as
  // one cycle gains less than 2x, conjugate gradients take over with the (symmetric) cycle as
  // preconditioner, which removes those modes in a few iterations. Off: V-cycles only.
  bool krylov = true;
  int max_levels = 0;  // 0: coarsen down to <= 64 points; otherwise at most this many levels
  // Away from curves every coarse point has the same prolongation weights and Galerkin stencil, to
  // the last bit: one is computed and copied to the others. Off: each is computed on its own, and
  // the prolongation from the finest level a point at a time rather than sixteen (the same bits,
  // slower; the reference for tests).
  bool copy_plain_stencils = true;
  // Called after the FMG start and after every cycle with the entry of residual_history it
  // matches and the residual b - A u at every pixel (channel planes of W*H; 0 on fixed pixels).
  // For inspection tools; costs a copy per cycle when set.
  std::function<void(int step, const std::vector<float>& residual)> observer;
};

struct SolveStats {
  int levels = 0;
  int cycles = 0;                        // V-cycles (or CG iterations) after the FMG start
  int floating_pixels = 0;               // free pixels that no Dirichlet pixel reaches
  double initial_residual = 0;           // relative, max over channels, before any cycle
  double final_residual = 0;             // relative, max over channels
  std::vector<double> residual_history;  // after FMG, then after each V-cycle
  // With SolverOptions::max_error: the estimated largest error after FMG and after each cycle
  // (infinity where no estimate could be made).
  std::vector<double> error_estimates;
  double setup_ms = 0;
  double solve_ms = 0;
  // Where the cycles' time went, per level (finest first): each level's own passes (its
  // smoothing, with the residual, restriction and prolongation that run inside those waves; the
  // coarsest level's exact solve), summed over the solve. Their sum is most of solve_ms.
  std::vector<double> level_ms;
  bool converged = false;
};

struct Solution {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> planes;  // channels planes of width*height
  SolveStats stats;
};

// Asymptotic convergence factors of the plain V-cycle on `problem`: V-cycles are applied to the
// error equation A e = 0 from a seeded random start, the error rescaled after every cycle (so
// float32 precision never runs out), and the factor ||r_k+1|| / ||r_k|| of each cycle returned.
// This is how the rate of a multigrid cycle is measured (Trottenberg et al., Multigrid, 2001).
std::vector<double> measure_vcycle_factors(const Problem& problem, int cycles,
                                           const SolverOptions& options = {}, unsigned seed = 1);

// Solves `problem`. `initial_guess`, when given (a warm start, e.g. the previous frame), holds
// channels planes of W*H; its values at fixed pixels are ignored.
Solution solve_multigrid(const Problem& problem, const SolverOptions& options = {},
                         const std::vector<float>* initial_guess = nullptr);
// The same, the answer written over the initial guess's own buffer: no fresh planes to allocate
// and fault in (a frame's warm start, which is not needed after the solve).
Solution solve_multigrid(const Problem& problem, const SolverOptions& options,
                         std::vector<float>&& initial_guess);

// A solve from nothing (no initial guess), its answer written into `storage`, whose values and
// size do not matter: a caller that solves drawing after drawing hands back its last answer's
// planes, so that the answer is not new memory to fault in (12.6 MB at 1024², three channels,
// which the allocator returns to the system as soon as it is freed).
Solution solve_multigrid_into(const Problem& problem, const SolverOptions& options,
                              std::vector<float>&& storage);

// Frees the workspaces that solves keep between calls (about 84 MB at 1024², three channels):
// the next solve builds a new one. For the end of a batch, e.g. before `wisp render`'s previews.
void release_solver_workspaces();

}  // namespace wisp::diffusion
