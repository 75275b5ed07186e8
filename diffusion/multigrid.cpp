// Black-box geometric multigrid for the constrained 5-point problem (see multigrid.hpp).
//
// Storage: every level keeps its arrays on a grid padded by one ghost point on each side, so
// stencils never branch at the border: ghost values and couplings to ghosts are zero.
// Operator at point p:  (A e)_p = diag_p e_p - sum_q a_pq e_q  over the 8 neighbours, with the
// couplings stored once per pair: east, south, south-east and south-west of p. The finest level
// stores its 0/1 couplings and its link counts as a byte per point (Level::code).
#include "diffusion/multigrid.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <stdexcept>
#include <type_traits>

#include "diffusion/fresh_memory.hpp"
#include "diffusion/timer.hpp"

namespace wisp::diffusion {
namespace {

// Runs body(y0, y1) over rows [0, rows) in parallel chunks of about `points_per_task` points.
template <class Body>
void for_rows(int rows, int row_length, const Body& body) {
  constexpr int kPointsPerTask = 16384;
  const int grain = std::max(1, kPointsPerTask / std::max(1, row_length));
  if (rows <= grain) {
    body(0, rows);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, rows, grain),
                    [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
}

// A level's arrays: assign_touched fills them by the worker threads together
// (fresh_memory.hpp), and nothing reads an element before a fill or a pass has written it.
using Plane = UninitializedVector<float>;
using Flags = UninitializedVector<std::uint8_t>;

// v[i] = 0 for every i, by the worker threads together: a 1024^2 frame's correction is 12 MB,
// about a millisecond of one thread's stores.
void fill_zero(Plane& v) {
  assign_touched(v, v.size(), 0.0f);
}

// Asks for the cache line of base[offset] ahead of its use. The passes below read many arrays a
// row at a time, more streams than the hardware prefetcher follows (and the finest level's
// diagonal only at anchored points, which it cannot predict): a row's loads waited for memory
// (`wisp-bench solver`, 1024^2: the solve's cycles 17 % faster with these hints). A prefetch
// never faults, so the address may lie past the array's end (at the last rows); it is formed
// as an integer, not as a pointer out of bounds.
template <class T>
inline void prefetch(const T* base, std::ptrdiff_t offset) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(base) +
                                                   offset * std::ptrdiff_t(sizeof(T))));
}

// The stopping rule of SolverOptions::max_error. A cycle maps the error e to M e; it changed the
// answer by delta = e - M e and reduced the residual by rho. If later cycles keep that rate, the
// error left is M e = M (I - M)^-1 delta, at most delta * rho / (1 - rho). The largest change over
// the pixels stands for the largest error (both are dominated by the slowest, smoothest mode), and
// kErrorSafety covers what the residual ratio and the max norm miss (calibrated against Eigen's
// LDLT in test_multigrid.cpp, which also checks that the rule is not looser than needed).
constexpr double kErrorSafety = 2.0;

double error_estimate(double delta, double rho) {
  if (delta == 0) return 0;
  if (!(rho < 0.9)) return std::numeric_limits<double>::infinity();
  return kErrorSafety * delta * rho / (1 - rho);
}

// Bits of Level::code.
constexpr std::uint8_t kCodeEast = 1;      // coupled to the east neighbour: ae = 1
constexpr std::uint8_t kCodeSouth = 2;     // coupled to the south neighbour: as = 1
constexpr std::uint8_t kCodeAnchored = 4;  // diag and inv_diag are not the link count's
constexpr int kCodeLinksShift = 4;         // open links (0 on fixed points): diag, if not anchored

// The finest level's diagonal (and its inverse) at a point that is not anchored, by its count of
// open links (Level::code): the same floats as float(links) + 0 and 1.0f / that.
constexpr float kLinksDiag[16] = {0, 1, 2, 3, 4};
constexpr float kLinksInverse[16] = {0, 1.0f / 1, 1.0f / 2, 1.0f / 3, 1.0f / 4};

struct Level {
  int w = 0, h = 0;  // interior size
  int stride = 0;    // kLeft + w + 1, rounded up to a whole number of 64-byte lines
  bool nine_point = false;
  Plane diag, inv_diag;    // inv_diag is 0 on fixed points: the smoother keeps e = 0
  Plane ae, as, ase, asw;  // empty on the finest level (see code)
  // The finest level's couplings are 0 or 1 (a link open between two free points, or not) and
  // its diagonal the count of open links, plus the anchor weight where there is one: `code` holds
  // them in a byte a point, which the cycles read instead of 16 bytes of floats. There diag holds
  // the diagonal only where a point is anchored (see diag_of()), and inv_diag is empty (the
  // cycles read pinv_diag below).
  Flags code;
  Flags alive;  // 1 on free points
  // Coarse levels: 1 where the point's stored stencil is the level's plain one (see
  // PlainPoints), copied from the one point that computed it. Set by each setup.
  Flags plain;
  // Prolongation into this level from the next coarser one, stored per coarse cell on the coarse
  // level's padded grid (see Level::p below): weights of the fine points of coarse cell (I,J).
  Plane e, rhs;  // channel planes, padded

  // The finest level's values (e, rhs, and every plane of its points: vat()) are stored with
  // each row's even points first, from kLeft, and its odd ones after, from `odd` (0 on the coarse
  // levels, whose rows are in order). A colour of the red-black smoother is then one half of a
  // row: sixteen of its points are one load and one store, their east and west neighbours two
  // loads from the other half, their north and south ones the same half of the rows around
  // (docs/performance.md, "The finest level by columns": its relaxation about 1.5x faster). Its
  // operator arrays (code, alive, diag) stay in order for the setup's products, and the cycles
  // read copies of the code and anchored diagonals in the values' layout.
  int odd = 0;
  Flags pcode;             // finest: code, at vat()
  Plane pdiag, pinv_diag;  // finest: diag and inv_diag at vat(), where anchored

  // Each row's first point sits at the start of a 64-byte line (a Plane's storage starts on
  // one), its ghost x = -1 at the end of the line before: the passes' loads of sixteen points
  // at x then read one line, not two (1024^2 cycles 15 % faster: docs/performance.md).
  static constexpr int kLeft = 16;
  static int stride_for(int w) { return (kLeft + w + 1 + 15) / 16 * 16; }
  size_t padded() const { return size_t(stride) * size_t(h + 2); }
  size_t at(int x, int y) const { return size_t(y + 1) * stride + size_t(x + kLeft); }
  // Where the value of point (x, y) is, for x in [-1, w]: x = -1 and x = w are ghosts (0).
  size_t vat(int x, int y) const {
    if (odd == 0) return at(x, y);
    return size_t(y + 1) * stride + size_t((x & 1 ? odd : kLeft) + (x >> 1));
  }
  int even_count() const { return (w + 1) / 2; }
  int odd_count() const { return w / 2; }
  // The runs of a row's values: `count` points from `offset` past the row's x = 0 (at()). One
  // run on the coarse levels; two on the finest, its even points, then its odd ones.
  struct Run {
    int offset, count;
  };
  std::array<Run, 2> runs() const {
    if (odd == 0) return {Run{0, w}, Run{0, 0}};
    return {Run{0, even_count()}, Run{odd - kLeft, odd_count()}};
  }
  // The ghost values of a row (relative to its x = 0) that a pass reads: 0 in any row array.
  std::array<int, 3> ghosts() const {
    if (odd == 0) return {-1, w, w};
    return {even_count(), odd - kLeft - 1, odd - kLeft + odd_count()};
  }
  // The finest level's layout: even points from kLeft with a ghost after them, the odd ones
  // from the next line, with a ghost before and after.
  void lay_out_by_columns() {
    odd = (kLeft + even_count() + 1 + 15) / 16 * 16;
    stride = (odd + odd_count() + 1 + 15) / 16 * 16;
  }
};

// e = 0 on row y of level L, every channel (its ghosts are 0 already).
void zero_row(Level& L, int y) {
  const size_t n = L.padded();
  for (size_t c = 0; c < L.e.size() / n; ++c)
    for (const Level::Run& run : L.runs())
      std::fill_n(&L.e[c * n + L.at(0, y) + run.offset], run.count, 0.0f);
}

// Weights of the fine points of coarse cell (I,J) (stored on the coarse level's padded grid):
//   x0, x1: fine (2I+1, 2J) from coarse (I,J) and (I+1,J)
//   y0, y1: fine (2I, 2J+1) from coarse (I,J) and (I,J+1)
//   c00, c10, c01, c11: fine (2I+1, 2J+1) from (I,J), (I+1,J), (I,J+1), (I+1,J+1)
struct Prolongation {
  Plane x0, x1, y0, y1, c00, c10, c01, c11;
};

// The arrays of a solve that outlive it: levels, prolongations and the fixed mask.
// Kept between solves (see solve_in_workspace), so solves reuse its allocations: at 1024^2 a
// fresh set costs about 70 MB of page faults per frame, a fifth of the solve. They also keep
// the operators, so that the next solve of the same size rebuilds only the coarse points whose
// stencils can have changed (consecutive frames differ around the hair only; see setup()).
struct Workspace {
  std::vector<Level> levels;
  std::vector<Prolongation> prolong;  // prolong[l]: from level l+1 into level l
  std::vector<std::uint8_t> fixed;
  Plane previous;
  // The size of the problem whose operators `levels` and `prolong` hold; 0 when they hold none
  // (or a setup did not finish).
  int width = 0, height = 0;
};

// Sets `stored` to `value` and says whether its bits changed. Stored either way (the same bits
// where they did not change): a branch on the test, at every array of every point, was
// mispredicted wherever the operator changes.
bool update(float& stored, float value) {
  std::uint32_t before, after;
  std::memcpy(&before, &stored, sizeof stored);
  std::memcpy(&after, &value, sizeof value);
  stored = value;
  return before != after;
}

// Per coarse column I of a fine row: whether any of the row's flags at fine x = 2I - r .. 2I + r
// is set, the places beyond the row counting as `outside`. The flags are written at row(); any()
// ORs the row, padded, over windows that double in width up to 2r + 1 (byte loops that
// vectorise: a prefix count of the row was a chain of dependent additions). One a task: it holds
// the row; sizes are its own members, not a level's, which the byte stores could alias.
class FlagWindows {
 public:
  FlagWindows(int fine_w, int radius)
      : fw_(fine_w), r_(radius), a_(size_t(fine_w + 4 * radius + 1), 0), b_(a_.size(), 0) {}
  std::uint8_t* row() { return a_.data() + r_; }  // fine x = 0 .. fine_w - 1
  void any(std::uint8_t outside, std::uint8_t* out, int cw) {
    const int span = 2 * r_ + 1, places = fw_ + 2 * r_;
    // (The padding again: the last row's windows may have written there.)
    std::fill_n(a_.data(), r_, outside);
    std::fill_n(a_.data() + r_ + fw_, r_, outside);
    // w[x]: any flag at padded places x .. x + width - 1, for the places that column windows
    // read (those past `places` only feed windows that none reads).
    std::uint8_t *w = a_.data(), *o = b_.data();
    for (int width = 1; width < span;) {
      const int step = std::min(width, span - width);  // width + step <= span
      for (int x = 0; x < places; ++x) o[x] = w[x] | w[x + step];
      std::swap(w, o);
      width += step;
    }
    for (int I = 0; I < cw; ++I) out[I] = w[2 * I];  // fine 2I - r .. 2I + r
  }

 private:
  int fw_, r_;
  std::vector<std::uint8_t> a_, b_;
};

// The coarse points of C (padded flags) within `radius` fine points, in both directions, of a
// fine point of F flagged in `changed` (padded flags on F).
std::vector<std::uint8_t> near_changed(const Level& F, const Level& C,
                                       const std::vector<std::uint8_t>& changed, int radius) {
  // Per fine row: which coarse columns have a flag within the radius (FlagWindows). Rows are
  // independent in both passes: they run in parallel. The second pass copies the sizes into
  // locals: a byte store may alias any int reached through a pointer (a level's, or a lambda's
  // capture), and the OR of rows below then reloaded its bound at every byte instead of running
  // 64 bytes at a time.
  std::vector<std::uint8_t> columns(size_t(F.h) * C.w);
  for_rows(F.h, F.w, [&](int y0, int y1) {
    FlagWindows windows(F.w, radius);
    for (int y = y0; y < y1; ++y) {
      std::copy_n(&changed[F.at(0, y)], F.w, windows.row());
      windows.any(0, &columns[size_t(y) * C.w], C.w);
    }
  });
  std::vector<std::uint8_t> out(C.padded(), 0);
  for_rows(C.h, C.w * (2 * radius + 1), [&](int J0, int J1) {
    const int fh = F.h, cw = C.w, r = radius;
    for (int J = J0; J < J1; ++J) {
      std::uint8_t* o = &out[C.at(0, J)];
      for (int y = std::max(0, 2 * J - r); y <= std::min(fh - 1, 2 * J + r); ++y) {
        const std::uint8_t* in = &columns[size_t(y) * cw];
#pragma GCC ivdep
        for (int I = 0; I < cw; ++I) o[I] |= in[I];
      }
    }
  });
  return out;
}

// Coarse points whose prolongation cell and Galerkin stencil are the plain ones: every fine point
// within 3 of their own (all that the cell and P^T A P read there) has the plain stencil. On the
// finest level that is a free, unanchored point linked to four free neighbours; on a coarse level
// a point whose stencil reads only stored values that are the level's plain ones (Level::plain:
// the point, its west neighbour and the three to its north). Plain cells and stencils are equal to
// the last bit, so one of them, `model` (the first that is to be rebuilt), is computed and copied
// to the others: most of an image is away from curves, on every level.
struct PlainPoints {
  Flags flags;                  // per padded coarse point
  std::optional<size_t> model;  // none when no plain point is to be rebuilt
  // What the setup does at each padded coarse point: kCompute its prolongation cell and stencil,
  // kCopy the model's (a plain point to be rebuilt that is not the model), or nothing (a point
  // an incremental rebuild keeps). One byte a point, read through a plain pointer by the loops
  // that build a level (a test of `flags`, `model` and the rebuild set at each point, through
  // references, was most of the Galerkin product's time on a new drawing).
  static constexpr std::uint8_t kCompute = 1, kCopy = 2;
  std::vector<std::uint8_t> todo;
};

PlainPoints plain_points(const Level& F, const Level& C, const std::vector<std::uint8_t>* rebuild,
                         bool copies) {
  PlainPoints out;
  out.flags.assign(C.padded(), 0);
  out.todo.assign(C.padded(), 0);
  const auto plan = [&] {
    const std::uint8_t* wanted = rebuild ? rebuild->data() : nullptr;
    const std::uint8_t* plain = out.flags.data();
    const size_t model = out.model.value_or(SIZE_MAX);  // (never a point's index)
    std::uint8_t* todo = out.todo.data();
    for_rows(C.h, C.w, [&](int J0, int J1) {
      for (int J = J0; J < J1; ++J)
        for (size_t kc = C.at(0, J); kc < C.at(C.w, J); ++kc) {  // selects: it vectorises
          const bool want = wanted ? wanted[kc] != 0 : true, copy = plain[kc] && kc != model;
          todo[kc] = want ? (copy ? PlainPoints::kCopy : PlainPoints::kCompute) : 0;
        }
    });
  };
  if (!copies || (F.nine_point && F.plain.empty())) {
    plan();
    return out;
  }
  const int fs = F.stride;
  // 1 where a fine point's stencil is not the plain one, for the points of row y: with & rather
  // than &&, no branch (ivdep: `bad` is none of the level's arrays).
  const auto not_plain = [&](int y, std::uint8_t* bad) {
    // Sizes as locals of the loops: the byte stores may alias anything, so a member or a captured
    // reference would be read again at every step.
    const int fw = F.w, stride = fs;
    const size_t k0 = F.at(0, y);
    if (F.nine_point) {
      const std::uint8_t* v = F.plain.data() + k0;
      const std::uint8_t* n = v - stride;
      for (int x = 0; x < fw; ++x) bad[x] = !(v[x] & v[x - 1] & n[x] & n[x - 1] & n[x + 1]);
      return;
    }
    const std::uint8_t *code = F.code.data() + k0, *alive = F.alive.data() + k0;
    const float* diag = F.diag.data() + k0;
    // The stored diagonal's test in a loop of its own: with floats and bytes in one loop, GCC
    // kept it scalar, a branch a point.
#pragma GCC ivdep
    for (int x = 0; x < fw; ++x) bad[x] = diag[x] == 4.0f;
#pragma GCC ivdep
    for (int x = 0; x < fw; ++x) {
      const std::uint8_t c = code[x];
      const std::uint8_t four = c & kCodeAnchored ? bad[x] : c >> kCodeLinksShift == 4;
      bad[x] = !(alive[x] & four & ((c & kCodeEast) != 0) & ((c & kCodeSouth) != 0) &
                 ((code[x - 1] & kCodeEast) != 0) & ((code[x - stride] & kCodeSouth) != 0));
    }
  };
  // Per fine row, per coarse column I: whether fine points 2I-3 .. 2I+3 of the row are all plain
  // (none is flagged not plain, nor beyond the row: FlagWindows); then per coarse point, whether
  // rows 2J-3 .. 2J+3 all say so.
  std::vector<std::uint8_t> columns(size_t(F.h) * C.w);
  for_rows(F.h, F.w, [&](int y0, int y1) {
    FlagWindows windows(F.w, 3);
    const int cw = C.w;
    for (int y = y0; y < y1; ++y) {
      not_plain(y, windows.row());
      std::uint8_t* row = &columns[size_t(y) * cw];
      windows.any(1, row, cw);
      for (int I = 0; I < cw; ++I) row[I] ^= 1;
    }
  });
  for_rows(C.h, C.w * 7, [&](int J0, int J1) {
    for (int J = J0; J < J1; ++J) {
      const int y0 = 2 * J - 3, y1 = 2 * J + 4;
      if (y0 < 0 || y1 > F.h) continue;
      std::uint8_t* o = &out.flags[C.at(0, J)];
      const int cw = C.w;
      for (int I = 0; I < cw; ++I) o[I] = 1;
      for (int y = y0; y < y1; ++y) {
        const std::uint8_t* in = &columns[size_t(y) * cw];
#pragma GCC ivdep
        for (int I = 0; I < cw; ++I) o[I] &= in[I];
      }
    }
  });
  for (size_t k = 0; k < out.flags.size(); ++k)
    if (out.flags[k] && (!rebuild || (*rebuild)[k])) {
      out.model = k;
      break;
    }
  plan();
  return out;
}

// How far, in fine points, a change of the fine operator reaches into the coarse level. Point q's
// stencil reads what is stored at q and at its west, north-west, north and north-east neighbours
// (Level: each coupling is stored once, at one of its two points). A prolongation row reads its
// point's stencil and the coarse alive flags around it; a cell centre's also reads its four edge
// neighbours' stencils (through their weights): at most 2 points from the centre. The Galerkin
// stencil of coarse point K reads the stencils of the fine points within 1 of 2K and the
// prolongation rows of those within 2: edge points' rows, which read what is stored within 1 of
// them, and centres' rows, which read within 2, but the centres near K are all within 1 of 2K.
// That is 3. The tests check it: an incremental rebuild gives a full one's bits, and one that
// reaches 2 does not (at 6, the old margin, a new drawing's setup rebuilt about a fifth more).
constexpr int kChangeReach = 3;

using RowHook = std::function<void(int)>;
// Called for row y of the finest level after a cycle, with the squared norms of its residual's
// channels (the stopping rule's measurement).
using MeasureHook = std::function<void(int y, const float* norms)>;

// Where a cycle of a level starts (Multigrid::vcycle).
enum class CycleStart {
  kHeld,        // the correction the level holds, pre-smoothed
  kZero,        // the correction 0, pre-smoothed: the pre-smoothing's wave writes each row's zeros
                // just before its first stage reads it (rather than a pass of their own)
  kFromCoarse,  // full multigrid: the next coarser level's correction, prolongated (the
                // pre-smoothing's wave writes each row just before its first stage reads it)
  kRestricted,  // the coarse correction: the last cycle's post-smoothing was the level's last
                // smoothing, and it restricted the residual it left to the next coarser level
};

// What a row of a level becomes in the prolongation of the next coarser level's correction
// (Multigrid::prolongate_row): e + P e_c (kAdd), 0 + P e_c (kSet), or from + P e_c for another
// plane `from` of the level's layout (kFrom: e's values kept there, for the stopping rule).
enum class Prolong { kAdd, kSet, kFrom };

// The restriction of a level's rows as they are completed, in any order, by rows in parallel:
// coarse row J reads fine rows 2J-1 .. 2J+1, and is restricted by the call that completes the
// last of them.
class RestrictWhenReady {
 public:
  RestrictWhenReady(int fine_h, int coarse_h)
      : fine_h_(fine_h), coarse_h_(coarse_h), ready_(new std::atomic<int>[size_t(coarse_h)]) {
    for (int J = 0; J < coarse_h; ++J) ready_[J].store(0, std::memory_order_relaxed);
  }
  // Fine row y is final: restrict(J) for each coarse row J that it completes.
  template <class Restrict>
  void row_done(int y, const Restrict& restrict) {
    for (int J = y / 2; J <= std::min(coarse_h_ - 1, (y + 1) / 2); ++J) {
      const int needed = std::min(fine_h_ - 1, 2 * J + 1) - std::max(0, 2 * J - 1) + 1;
      if (ready_[J].fetch_add(1, std::memory_order_acq_rel) + 1 == needed) restrict(J);
    }
  }

 private:
  int fine_h_, coarse_h_;
  std::unique_ptr<std::atomic<int>[]> ready_;
};

template <int NC>
class Multigrid {
 public:
  Multigrid(const Problem& problem, const SolverOptions& options, Workspace& ws)
      : problem_(problem),
        options_(options),
        ws_(ws),
        levels_(ws.levels),
        prolong_(ws.prolong),
        fixed_(ws.fixed),
        previous_(ws.previous) {}

  // `buffer`, when given, is taken for the answer's planes (it may hold the initial guess).
  Solution run(const std::vector<float>* initial_guess, std::vector<float>* buffer = nullptr);
  std::vector<double> factors(int cycles, unsigned seed);

 private:
  const Problem& problem_;
  const SolverOptions& options_;
  Workspace& ws_;
  std::vector<Level>& levels_;
  std::vector<Prolongation>& prolong_;  // prolong_[l]: from level l+1 into level l
  std::array<double, NC> b_norm_{};     // scale of relative residuals (see relative())
  std::vector<std::uint8_t>& fixed_;    // the problem's fixed pixels plus the unreachable ones
  Plane& previous_;                     // the correction before a cycle (SolverOptions::max_error)
  bool previous_zero_ = false;          // previous_ stands for zeros (its contents are not read)
  std::vector<double> level_ms_;        // SolveStats::level_ms
  // Exact solver of the coarsest level.
  Eigen::LDLT<Eigen::MatrixXd> coarse_ldlt_;
  std::vector<size_t> coarse_points_;  // its free points (at()), and where their values are (vat())
  std::vector<size_t> coarse_values_;

  int mark_fixed(std::vector<std::uint8_t>& fixed) const;
  // The builders of the levels' operators return which points' stored operator (diagonal,
  // couplings, alive) changed, as padded flags; `rebuild` is the points to compute (padded flags
  // on the level built; nullptr: every point, on freshly zeroed arrays, and nothing is returned).
  std::vector<std::uint8_t> build_finest(const std::vector<std::uint8_t>& fixed, bool full);
  std::vector<std::uint8_t> build_coarse(int l, const std::vector<std::uint8_t>* changed);
  // prolong_[l], once levels_[l + 1] knows its points
  void build_prolongation(int l, const std::vector<std::uint8_t>* rebuild,
                          const PlainPoints& plain);
  // The operator of levels_[l + 1]: P^T A_l P
  std::vector<std::uint8_t> galerkin_product(int l, const std::vector<std::uint8_t>* rebuild,
                                             const PlainPoints& plain);
  void build_coarsest();
  // `row_done`, when given, is called once for every row y of the level as soon as rows y-1..y+1
  // have their final values (rows in parallel), while they are still in cache.
  // `row_first`, when given, is called once for every row y of the level before any stage
  // reads it (rows in parallel): the prolongation, in the post-smoothing's wave.
  void smooth(int l, int sweeps, bool reverse, const RowHook* row_done = nullptr,
              const RowHook* row_first = nullptr);
  void relax_finest_row(Level& F, int y, int half);
  void relax_row(Level& L, int y, int x_parity);
  // Both colours of row y of a 9-point level: parity `first`, then the other (see smooth()).
  void relax_row_pair(Level& L, int y, int first);
  void residual_row(int l, int y, const Plane* b, const Plane& e, float* const out[NC],
                    float* norms) const;
  void residual_of(int l, const Plane* b, const Plane& e, Plane* out,
                   std::vector<double>* row_norms = nullptr) const;
  std::array<double, NC> residual_norms(int l) const;
  std::array<double, NC> sum_row_norms(const std::vector<double>& rows, int h) const;
  // Row J of levels_[l+1].rhs = P^T r, from r on fine rows 2J-1, 2J, 2J+1 (per channel, each
  // pointing at x = 0 of a row readable from x = -1 to w, zero outside the level).
  void restrict_row(int l, int J, const float* const north[NC], const float* const centre[NC],
                    const float* const south[NC]);
  // Row J of levels_[l+1].rhs = P^T levels_[l].rhs.
  void restrict_rhs_row(int l, int J);
  // Row y of levels_[l].e += P levels_[l+1].e, or as kMode says (`from`: Prolong::kFrom's plane).
  template <Prolong kMode>
  void prolongate_row(int l, int y, const Plane* from = nullptr);
  void solve_coarsest();
  // `measure`: called for every row after the post-smoothing (see smooth()), with its residual's
  // squared norms; the wave then also restricts that residual, for a next cycle that starts
  // with CycleStart::kRestricted, unless `last` (the cycle is expected to be the solve's last:
  // restrict_residual does it if another one follows). `before`: a plane of the level's layout,
  // with zero ghosts, that the cycle leaves holding e as the cycle found it (the stopping rule's
  // change, measured as the post-smoothing ends: see there).
  void vcycle(int l, const MeasureHook* measure = nullptr, CycleStart start = CycleStart::kHeld,
              Plane* before = nullptr, bool last = false);
  // A smoothing wave's row_done hook that computes the residual of level l row by row and
  // restricts it to level l+1 as `ready` says (with `measure`, also measures it; see vcycle).
  RowHook restricting(int l, RestrictWhenReady& ready, const MeasureHook* measure);
  // levels_[l+1].rhs = P^T (b - A e) of level l: what a measured cycle's wave restricts, in a pass
  // of its own.
  void restrict_residual(int l);
  double relative(const std::array<double, NC>& norms) const;
  double conjugate_gradient(double rel, double tolerance, SolveStats& st);
  void setup();
  // `u` null: no initial guess (see residual_double).
  // `row_done`, when given, is called for every row once it is written (rows in parallel).
  template <class T>
  std::array<double, NC> residual_double(const T* u, Plane& r_padded,
                                         std::array<double, NC>* b_norms = nullptr,
                                         const RowHook* row_done = nullptr) const;
  double solve_correction(double rel, double tolerance, SolveStats& st);
  // The largest change of row y of the finest level's correction since previous_, over its
  // points and channels.
  float change_of_row(int y) const;
  // Hands SolverOptions::observer the residual: `residual_padded`, or the finest level's.
  void observe(const Plane* residual_padded, const SolveStats& st) const;
  std::array<double, NC> dot(const Plane& a, const Plane& b) const;
};

// Pixels not connected through open links to any Dirichlet pixel are fixed to 0 (their value is
// undefined). Returns how many there were.
template <int NC>
int Multigrid<NC>::mark_fixed(std::vector<std::uint8_t>& fixed) const {
  const Problem& p = problem_;
  const std::vector<std::uint8_t> reached = reached_from_fixed(p);
  std::atomic<int> floating{0};  // a sum of integers: the same in any order
  fixed.resize(p.pixel_count());
  for_rows(p.height, p.width, [&](int y0, int y1) {
    // Bounds and arrays as locals: the byte stores may alias anything reached by reference.
    const size_t i0 = p.index(0, y0), i1 = p.index(0, y1);
    const std::uint8_t *given = p.fixed.data(), *seen = reached.data();
    std::uint8_t* out = fixed.data();
    int here = 0;
#pragma GCC ivdep
    for (size_t i = i0; i < i1; ++i) {
      out[i] = std::uint8_t((given[i] != 0) | !seen[i]);  // 0 or 1, whatever p.fixed holds
      here += !seen[i];
    }
    floating += here;
  });
  return floating;
}

// The codes (Level::code) and alive flags of `count` points of a row of the finest level, from
// the problem's links of the points, their west neighbours (`west`) and north neighbours, and the
// fixed flags of the points and their east and south neighbours; with kTrack, `changed` says
// which of them differ from what code and alive held. No branch: it vectorises.
template <bool kTrack>
void finest_codes(int count, const std::uint8_t* __restrict links,
                  const std::uint8_t* __restrict west, const std::uint8_t* __restrict north,
                  const std::uint8_t* __restrict fixed, const std::uint8_t* __restrict east,
                  const std::uint8_t* __restrict south, const float* __restrict weight,
                  std::uint8_t* __restrict code, std::uint8_t* __restrict alive,
                  std::uint8_t* __restrict changed) {
  for (int x = 0; x < count; ++x) {
    const int open_e = links[x] & kOpenEast, open_s = (links[x] & kOpenSouth) >> 1;
    const int open_w = west[x] & kOpenEast, open_n = (north[x] & kOpenSouth) >> 1;
    const int is_free = fixed[x] ^ 1;
    const int c = ((open_e + open_s + open_w + open_n) << kCodeLinksShift | (weight[x] > 0) << 2 |
                   (open_s & (south[x] ^ 1)) << 1 | (open_e & (east[x] ^ 1))) *
                  is_free;
    if constexpr (kTrack) changed[x] = (alive[x] != is_free) | (code[x] != c);
    alive[x] = std::uint8_t(is_free);
    code[x] = std::uint8_t(c);
  }
}

// Finest level: the negative 5-point Laplacian over open links, restricted to free pixels.
// The diagonal counts every open link (also those to fixed pixels, whose values are data) and the
// pixel's anchor weight: an anchor is a link to a neighbour that holds data. The Galerkin coarse
// levels and the smoother see anchors through the diagonal only.
template <int NC>
std::vector<std::uint8_t> Multigrid<NC>::build_finest(const std::vector<std::uint8_t>& fixed,
                                                      bool full) {
  const Problem& p = problem_;
  Level& L = levels_[0];
  L.w = p.width;
  L.h = p.height;
  L.lay_out_by_columns();
  L.nine_point = false;
  const size_t n = L.padded();
  std::vector<std::uint8_t> changed;
  if (full) {
    for (auto* v : {&L.diag, &L.pdiag, &L.pinv_diag}) assign_touched(*v, n, 0.0f);
    for (auto* v : {&L.code, &L.alive, &L.pcode}) assign_touched(*v, n, std::uint8_t(0));
  } else {
    changed.assign(n, 0);
  }
  const int W = p.width, H = p.height;
  const std::vector<std::uint8_t> no_links(size_t(W), 0);
  for_rows(H, W, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t row = p.index(0, y), k0 = L.at(0, y);
      const std::uint8_t* links = &p.links[row];
      const std::uint8_t* north = y > 0 ? links - W : no_links.data();
      const std::uint8_t* fixed_row = &fixed[row];
      const std::uint8_t* south = y + 1 < H ? fixed_row + W : fixed_row;  // (no link there)
      const float* weight = &p.anchor_weight[row];
      std::uint8_t *code = &L.code[k0], *alive = &L.alive[k0];
      std::uint8_t* changed_row = full ? nullptr : &changed[k0];
      const std::uint8_t none = 0, one = 1;
      const auto codes = [&](int x, int count, const std::uint8_t* west, const std::uint8_t* east) {
        const auto run = [&](auto track) {
          finest_codes<decltype(track)::value>(count, links + x, west, north + x, fixed_row + x,
                                               east, south + x, weight + x, code + x, alive + x,
                                               track ? changed_row + x : nullptr);
        };
        if (changed_row)
          run(std::true_type{});
        else
          run(std::false_type{});
      };
      // The first and last points apart (no west link, no east neighbour).
      codes(0, 1, &none, W > 1 ? fixed_row + 1 : &one);
      if (W > 2) codes(1, W - 2, links, fixed_row + 2);
      if (W > 1) codes(W - 1, 1, links + W - 2, &one);
      // The cycles' copy of the codes, even points then odd ones (Level::odd). Counts as locals:
      // the byte stores may alias anything reached by reference.
      std::uint8_t* __restrict even = &L.pcode[L.vat(0, y)];
      std::uint8_t* __restrict odd = &L.pcode[L.vat(1, y)];
      const std::uint8_t* __restrict in_order = code;
      const int evens = L.even_count(), odds = L.odd_count();
      for (int i = 0; i < evens; ++i) even[i] = in_order[2 * i];
      for (int i = 0; i < odds; ++i) odd[i] = in_order[2 * i + 1];
      // The diagonal of anchored points (elsewhere it is the code's: diag_of()). They lie along
      // the curves: the codes are tested eight at a time, and a group without one is passed
      // (a test and a branch at every point were most of this function's time).
      const std::uint64_t anchored8 = 0x0101010101010101ull * kCodeAnchored;
      for (int x = 0, w = W; x < w; ++x) {
        if ((x & 7) == 0 && x + 8 <= w) {
          std::uint64_t group;
          std::memcpy(&group, code + x, 8);
          if (!(group & anchored8)) {
            x += 7;
            continue;
          }
        }
        if (!(code[x] & kCodeAnchored)) continue;
        const float diag = float(code[x] >> kCodeLinksShift) + weight[x];
        if (update(L.diag[k0 + x], diag) && changed_row) changed_row[x] = 1;
        L.pdiag[L.vat(x, y)] = diag;
        L.pinv_diag[L.vat(x, y)] = 1.0f / diag;
      }
    }
  });
  return changed;
}

// The operator of a level around one of its points, with the couplings to all eight neighbours
// (zero where the level is 5-point).
struct Stencil {
  float d, e, w, n, s, ne, nw, se, sw;
};

float coupling(const Plane& v, size_t k) {
  return v.empty() ? 0.0f : v[k];
}

// The diagonal at point k (on the finest level from its code, but where it is anchored).
float diag_of(const Level& L, size_t k) {
  if (L.code.empty() || (L.code[k] & kCodeAnchored)) return L.diag[k];
  return kLinksDiag[L.code[k] >> kCodeLinksShift];
}

// The couplings of point k to its east and south neighbours (on the finest level, from its code).
float east_of(const Level& L, size_t k) {
  return L.code.empty() ? L.ae[k] : (L.code[k] & kCodeEast ? 1.0f : 0.0f);
}
float south_of(const Level& L, size_t k) {
  return L.code.empty() ? L.as[k] : (L.code[k] & kCodeSouth ? 1.0f : 0.0f);
}

Stencil stencil_at(const Level& F, size_t k) {
  const int fs = F.stride;
  return Stencil{diag_of(F, k),
                 east_of(F, k),
                 east_of(F, k - 1),
                 south_of(F, k - fs),
                 south_of(F, k),
                 coupling(F.asw, k - fs + 1),
                 coupling(F.ase, k - fs - 1),
                 coupling(F.ase, k),
                 coupling(F.asw, k)};
}

// Level l+1: the even points of level l, with an operator-dependent prolongation into level l
// and the Galerkin coarse operator A_{l+1} = P^T A_l P.
// With `changed` (the fine points whose stored operator changed since the workspace's last
// setup), only the coarse points within kChangeReach of one are rebuilt: the others' prolongation
// and stencil cannot have changed, and the result is that of a full rebuild, bit for bit.
template <int NC>
std::vector<std::uint8_t> Multigrid<NC>::build_coarse(int l,
                                                      const std::vector<std::uint8_t>* changed) {
  const Level& F = levels_[l];
  Level& C = levels_[l + 1];
  C.w = (F.w + 1) / 2;
  C.h = (F.h + 1) / 2;
  C.stride = Level::stride_for(C.w);
  C.nine_point = true;
  const size_t nc = C.padded();
  std::vector<std::uint8_t> rebuild, alive_changed;
  if (!changed) {
    assign_touched(C.alive, nc, std::uint8_t(0));
    for_rows(C.h, C.w, [&](int J0, int J1) {
      const int cw = C.w;  // (a local: the byte stores may alias a reference's int)
      for (int J = J0; J < J1; ++J) {
        std::uint8_t* out = &C.alive[C.at(0, J)];
        const std::uint8_t* in = &F.alive[F.at(0, 2 * J)];
        for (int I = 0; I < cw; ++I) out[I] = in[2 * I];
      }
    });
  } else {
    rebuild = near_changed(F, C, *changed, kChangeReach);
    alive_changed.assign(nc, 0);
    // Rows in parallel, selects rather than a branch a point, and the arrays and sizes as locals
    // (the byte stores may alias anything reached by reference): it vectorises. A loop over
    // every point that tested `rebuild` first was a millisecond at 1024^2, on one thread.
    for_rows(C.h, C.w, [&](int J0, int J1) {
      const int cw = C.w;
      const std::uint8_t* const wanted = rebuild.data();
      const std::uint8_t* const fine = F.alive.data();
      std::uint8_t *const alive = C.alive.data(), *const differs = alive_changed.data();
      for (int J = J0; J < J1; ++J) {
        const size_t k0 = C.at(0, J);
        const std::uint8_t* const in = fine + F.at(0, 2 * J);
#pragma GCC ivdep
        for (int I = 0; I < cw; ++I) {
          const size_t kc = k0 + I;
          const std::uint8_t now = wanted[kc] ? in[2 * I] : alive[kc];
          differs[kc] = now != alive[kc];
          alive[kc] = now;
        }
      }
    });
  }
  const std::vector<std::uint8_t>* points = changed ? &rebuild : nullptr;
  PlainPoints plain = plain_points(F, C, points, options_.copy_plain_stencils);
  build_prolongation(l, points, plain);
  std::vector<std::uint8_t> out = galerkin_product(l, points, plain);
  // (Plain pointers and a local count: a byte store may alias the vectors' own members, which
  // kept this loop scalar, 0.2 ms at 1024^2.)
  std::uint8_t* const to = out.data();
  const std::uint8_t* const from = alive_changed.data();
  for (size_t k = 0, n = alive_changed.size(); k < n; ++k) to[k] |= from[k];
  C.plain = std::move(plain.flags);
  return out;
}

// A half row of the finest level (Level::odd): `count` points from `own`, point i at x = 2 i + half
// of row y; the other half's point i is at `other`, and point i's east and west neighbours are the
// other half's points i + half and i + half - 1, its north and south ones the same half's points
// i of the rows around (+- Level::stride).
struct HalfRow {
  size_t own, other;
  int count, half;
};
HalfRow half_row(const Level& F, int y, int half) {
  const size_t even = F.vat(0, y), odd = F.vat(1, y);
  return half ? HalfRow{odd, even, F.odd_count(), 1} : HalfRow{even, odd, F.even_count(), 0};
}

#if defined(__AVX512BW__) && defined(__AVX512VL__)
// The lanes of a block of sixteen that hold points, with `left` points left in the row from the
// block's first (none when left <= 0).
inline __mmask16 lanes_left(int left) {
  return left >= 16 ? __mmask16(0xFFFF) : left <= 0 ? __mmask16(0) : __mmask16((1u << left) - 1);
}

// The finest level's operator at points i .. i+15 of a half row (0 in the lanes outside `in`):
// the couplings to the four neighbours, and the diagonal or its inverse.
struct Coefficients16 {
  __m512 e, w, s, n, d;
};
inline Coefficients16 finest_coefficients(const Level& F, const HalfRow& r, int i, __mmask16 in,
                                          bool inverse) {
  const std::uint8_t* code = &F.pcode[r.own + i];
  const __m128i here = _mm_maskz_loadu_epi8(in, code),
                west = _mm_maskz_loadu_epi8(in, &F.pcode[r.other + i + r.half - 1]),
                north = _mm_maskz_loadu_epi8(in, code - F.stride);
  const __m512 one = _mm512_set1_ps(1.0f);
  const auto bit = [&](__m128i v, std::uint8_t b) {
    return _mm512_maskz_mov_ps(_mm_test_epi8_mask(v, _mm_set1_epi8(char(b))), one);
  };
  Coefficients16 k;
  k.e = bit(here, kCodeEast);
  k.w = bit(west, kCodeEast);
  k.s = bit(here, kCodeSouth);
  k.n = bit(north, kCodeSouth);
  const __m128i links = _mm_and_si128(_mm_srli_epi16(here, kCodeLinksShift), _mm_set1_epi8(7));
  k.d = _mm512_permutexvar_ps(_mm512_cvtepu8_epi32(links),
                              _mm512_loadu_ps(inverse ? kLinksInverse : kLinksDiag));
  // Anchored points are along the curves: most groups of sixteen have none.
  const __mmask16 anchored = _mm_test_epi8_mask(here, _mm_set1_epi8(char(kCodeAnchored)));
  const float* stored = (inverse ? F.pinv_diag : F.pdiag).data() + r.own + i;
  prefetch(stored, 64);  // four groups ahead
  if (anchored) k.d = _mm512_mask_loadu_ps(k.d, anchored, stored);
  return k;
}

// build_prolongation's weights sixteen coarse points of a row at a time: the points I .. I+15 of
// row J flagged in `compute`, with its formulas' operations in their order (the products that
// GCC contracts as fused multiply-adds, as such), so the same bits lane by lane. The finest
// level has no corner couplings: their terms add +0 to sums that are not -0, and subtract +0.
struct Points16 {                        // sixteen fine points of one parity of x in a row
  __m512 d, e, w, n, s, ne, nw, se, sw;  // as stencil_at() gives them
  __mmask16 alive;
};
// row[x0 + 2i], i = 0..15, for the places x0 + 2i <= last (0 past it): the even places of the 32
// from x0, loaded in two and picked in registers.
inline __m512 every_other(const float* row, int x0, int last) {
  const int left = last + 1 - x0;
  const __m512 lo = _mm512_maskz_loadu_ps(lanes_left(left), row + x0);
  const __m512 hi = _mm512_maskz_loadu_ps(lanes_left(left - 16), row + x0 + 16);
  return _mm512_permutex2var_ps(
      lo, _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30), hi);
}
// v at the points x = x0 + 2i, i = 0..15, of row y of a level in order (x0 >= -1; the places past
// the ghost at x = w read as 0).
inline __m512 every_other(const Level& L, const Plane& v, int x0, int y) {
  return every_other(&v[L.at(0, y)], x0, L.w);
}
// The fine points x = 2 (I0 + i) + parity of row y, for the lanes i in `in`. Always inlined:
// its registers are its caller's (and out of line, GCC 12 takes the intrinsics' undefined
// operands for uninitialised values).
[[gnu::always_inline]] inline Points16 points16(const Level& F, int I0, int parity, int y,
                                                __mmask16 in) {
  Points16 f;
  if (!F.code.empty()) {
    const Coefficients16 k = finest_coefficients(F, half_row(F, y, parity), I0, in, false);
    f.d = k.d, f.e = k.e, f.w = k.w, f.n = k.n, f.s = k.s;
    f.ne = f.nw = f.se = f.sw = _mm512_setzero_ps();
  } else {
    const int x = 2 * I0 + parity;
    f.d = every_other(F, F.diag, x, y);
    f.e = every_other(F, F.ae, x, y), f.w = every_other(F, F.ae, x - 1, y);
    f.n = every_other(F, F.as, x, y - 1), f.s = every_other(F, F.as, x, y);
    f.ne = every_other(F, F.asw, x + 1, y - 1), f.nw = every_other(F, F.ase, x - 1, y - 1);
    f.se = every_other(F, F.ase, x, y), f.sw = every_other(F, F.asw, x, y);
  }
  // The alive flags are in order: bytes x = 2 I0 .. 2 I0 + 31, this parity's every other one.
  const int left = F.w - 2 * I0;
  const __mmask32 bytes = left >= 32 ? ~__mmask32(0) : left <= 0 ? 0 : (__mmask32(1) << left) - 1;
  __m256i pairs = _mm256_maskz_loadu_epi8(bytes, &F.alive[F.at(2 * I0, y)]);
  if (parity) pairs = _mm256_srli_epi16(pairs, 8);
  f.alive = __mmask16(in & _mm_test_epi8_mask(_mm256_cvtepi16_epi8(pairs), _mm_set1_epi8(1)));
  return f;
}
// build_prolongation's Collapse, sixteen at a time.
struct Collapse16 {
  __m512 weight, self;
};
inline Collapse16 collapse16(__m512 direct, __m512 beside, __m512 coarse_alive, __m512 d) {
  const __mmask16 weak =
      _mm512_cmp_ps_mask(direct, _mm512_mul_ps(_mm512_set1_ps(1e-3f), d), _CMP_LE_OQ);
  const __mmask16 dead = _mm512_cmp_ps_mask(coarse_alive, _mm512_setzero_ps(), _CMP_EQ_OQ);
  return {_mm512_maskz_add_ps(__mmask16(~weak & ~dead), direct, beside),
          _mm512_maskz_mov_ps(weak, beside)};
}
// ratio() of build_prolongation: num / den where den > 1e-6, else 0.
inline __m512 ratio16(__m512 num, __m512 den) {
  const __mmask16 ok = _mm512_cmp_ps_mask(den, _mm512_set1_ps(1e-6f), _CMP_GT_OQ);
  return _mm512_maskz_div_ps(ok, num, den);
}
// The coarse alive flags of points I0 .. I0+15 from `at` (as 0 or 1).
// (The zero-masked conversions: GCC 12 takes the plain ones' undefined operands for uninitialised
// values in some of the places this is inlined.)
inline __m512 coarse_alive16(const std::uint8_t* at, __mmask16 in) {
  return _mm512_maskz_cvtepi32_ps(in, _mm512_maskz_cvtepu8_epi32(in, _mm_maskz_loadu_epi8(in, at)));
}
#endif

// Operator-dependent prolongation (Dendy 1982) from level l+1 into level l: each fine point
// interpolates from the coarse points around it with weights from its own stencil.
template <int NC>
void Multigrid<NC>::build_prolongation(int l, const std::vector<std::uint8_t>* rebuild,
                                       const PlainPoints& plain) {
  const Level& F = levels_[l];
  const Level& C = levels_[l + 1];
  const size_t nc = C.padded();
  const auto ratio = [](float num, float den) { return den > 1e-6f ? num / den : 0.0f; };

  // Collapsing the stencil of an edge point onto its two coarse neighbours (Dendy): the
  // couplings beside a coarse neighbour (say north-west and south-west for the west one) are
  // assumed to see that neighbour's value. That holds only if the neighbour is coupled to the
  // point at all. Where a barrier runs between them (no direct coupling, neighbour alive), those
  // couplings see the point's own side instead, so they join the point's own term; otherwise
  // the interpolation would reach across the barrier. A fixed neighbour keeps the classic rule:
  // its side sees the Dirichlet value 0 of the correction.
  struct Collapse {
    float weight, self;
  };
  const auto collapse = [](float direct, float beside, float alive, float diag) {
    if (direct <= 1e-3f * diag) return Collapse{0.0f, beside};
    if (alive == 0.0f) return Collapse{0.0f, 0.0f};
    return Collapse{direct + beside, 0.0f};
  };

  Prolongation& P = prolong_[l];
  if (!rebuild)
    for (auto* v : {&P.x0, &P.x1, &P.y0, &P.y1, &P.c00, &P.c10, &P.c01, &P.c11})
      assign_touched(*v, nc, 0.0f);
  const auto alive_c = [&](int I, int J) { return float(C.alive[C.at(I, J)]); };
  // Edge points first: the cell centres interpolate from them. Every weight of a rebuilt cell is
  // written (0 where its fine point is fixed or outside), so no earlier value stays. Plain cells
  // take the model's weights once it has them (before the centres, which read the edges').
  const auto cells = [&](const auto& body) {
    for_rows(C.h, C.w * 8, [&](int J0, int J1) {
      const std::uint8_t* todo = plain.todo.data();
      for (int J = J0; J < J1; ++J)
        for (int I = 0; I < C.w; ++I) {
          const size_t kc = C.at(I, J);
          if (todo[kc] == PlainPoints::kCompute) body(I, J, kc);
        }
    });
  };
  const auto copy_plain = [&](std::initializer_list<Plane*> weights) {
    if (!plain.model) return;
    for_rows(C.h, C.w, [&](int J0, int J1) {
      const std::uint8_t* todo = plain.todo.data();
      const size_t k0 = C.at(0, J0), k1 = C.at(0, J1);
      for (Plane* v : weights) {
        float* const to = v->data();
        const float model = to[*plain.model];
        for (size_t kc = k0; kc < k1; ++kc)
          if (todo[kc] == PlainPoints::kCopy) to[kc] = model;
      }
    });
  };
#if defined(__AVX512BW__) && defined(__AVX512VL__)
  // (SolverOptions::copy_plain_stencils off: the one-point path, the reference that tests
  // compare this one with.)
  if (options_.copy_plain_stencils) {
    // Sixteen coarse points at a time (points16()), the same bits.
    const auto rows = [&](const auto& sixteen) {
      for_rows(C.h, C.w * 8, [&](int J0, int J1) {
        const std::uint8_t* todo = plain.todo.data();
        const int cw = C.w;
        for (int J = J0; J < J1; ++J)
          for (int I0 = 0; I0 < cw; I0 += 16) {
            const size_t kc = C.at(I0, J);
            const __mmask16 in = lanes_left(cw - I0);
            const __mmask16 compute = _mm_mask_cmpeq_epi8_mask(
                in, _mm_maskz_loadu_epi8(in, todo + kc), _mm_set1_epi8(PlainPoints::kCompute));
            if (compute) sixteen(I0, J, kc, compute);
          }
      });
    };
    const auto store = [&](Plane& v, size_t kc, __mmask16 m, __m512 x) {
      _mm512_mask_storeu_ps(&v[kc], m, x);
    };
    const auto sub = [](__m512 a, __m512 b) { return _mm512_sub_ps(a, b); };
    const auto add = [](__m512 a, __m512 b) { return _mm512_add_ps(a, b); };
    rows([&](int I0, int J, size_t kc, __mmask16 compute) {
      const __m512 zero = _mm512_setzero_ps(), alive = coarse_alive16(&C.alive[kc], compute);
      __m512 x0 = zero, x1 = zero, y0 = zero, y1 = zero;
      // Fine points (2I+1, 2J), where 2I+1 < F.w.
      if (const __mmask16 xs = compute & lanes_left(F.odd_count() - I0)) {
        const Points16 f = points16(F, I0, 1, 2 * J, xs);
        const Collapse16 west = collapse16(f.w, add(f.nw, f.sw), alive, f.d);
        const Collapse16 east =
            collapse16(f.e, add(f.ne, f.se), coarse_alive16(&C.alive[kc + 1], compute), f.d);
        const __m512 den = sub(sub(sub(sub(f.d, f.n), f.s), west.self), east.self);
        x0 = _mm512_maskz_mov_ps(f.alive, ratio16(west.weight, den));
        x1 = _mm512_maskz_mov_ps(f.alive, ratio16(east.weight, den));
      }
      // Fine points (2I, 2J+1), where 2J+1 < F.h.
      if (2 * J + 1 < F.h) {
        const Points16 f = points16(F, I0, 0, 2 * J + 1, compute);
        const Collapse16 north = collapse16(f.n, add(f.nw, f.ne), alive, f.d);
        const Collapse16 south =
            collapse16(f.s, add(f.sw, f.se), coarse_alive16(&C.alive[kc + C.stride], compute), f.d);
        const __m512 den = sub(sub(sub(sub(f.d, f.w), f.e), north.self), south.self);
        y0 = _mm512_maskz_mov_ps(f.alive, ratio16(north.weight, den));
        y1 = _mm512_maskz_mov_ps(f.alive, ratio16(south.weight, den));
      }
      store(P.x0, kc, compute, x0);
      store(P.x1, kc, compute, x1);
      store(P.y0, kc, compute, y0);
      store(P.y1, kc, compute, y1);
    });
    copy_plain({&P.x0, &P.x1, &P.y0, &P.y1});
    rows([&](int I0, int J, size_t kc, __mmask16 compute) {
      const __m512 zero = _mm512_setzero_ps();
      __m512 c00 = zero, c10 = zero, c01 = zero, c11 = zero;
      // Fine points (2I+1, 2J+1), where 2I+1 < F.w and 2J+1 < F.h.
      const __mmask16 cs = compute & lanes_left(F.odd_count() - I0);
      if (cs && 2 * J + 1 < F.h) {
        const Points16 f = points16(F, I0, 1, 2 * J + 1, cs);
        const __m512 inv = ratio16(_mm512_set1_ps(1.0f), f.d);
        const auto load = [&](const Plane& v, size_t k) {
          return _mm512_maskz_loadu_ps(cs, &v[k]);
        };
        const size_t below = kc + C.stride;
        // (a pa + b pb + corner alive) * inv, with the fused multiply-adds that GCC makes of the
        // one-point formula: corner alive + (a pa + (b pb))
        const auto weight = [&](__m512 a, __m512 pa, __m512 b, __m512 pb, __m512 corner,
                                const std::uint8_t* alive) {
          const __m512 sum = _mm512_fmadd_ps(corner, coarse_alive16(alive, cs),
                                             _mm512_fmadd_ps(a, pa, _mm512_mul_ps(b, pb)));
          return _mm512_maskz_mov_ps(f.alive, _mm512_mul_ps(sum, inv));
        };
        c00 = weight(f.w, load(P.y0, kc), f.n, load(P.x0, kc), f.nw, &C.alive[kc]);
        c10 = weight(f.e, load(P.y0, kc + 1), f.n, load(P.x1, kc), f.ne, &C.alive[kc + 1]);
        c01 = weight(f.w, load(P.y1, kc), f.s, load(P.x0, below), f.sw, &C.alive[below]);
        c11 = weight(f.e, load(P.y1, kc + 1), f.s, load(P.x1, below), f.se, &C.alive[below + 1]);
      }
      store(P.c00, kc, compute, c00);
      store(P.c10, kc, compute, c10);
      store(P.c01, kc, compute, c01);
      store(P.c11, kc, compute, c11);
    });
    copy_plain({&P.c00, &P.c10, &P.c01, &P.c11});
    return;
  }
#endif
  cells([&](int I, int J, size_t kc) {
    float x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    if (2 * I + 1 < F.w) {
      const size_t k = F.at(2 * I + 1, 2 * J);
      if (F.alive[k]) {
        const Stencil s = stencil_at(F, k);
        const Collapse west = collapse(s.w, s.nw + s.sw, alive_c(I, J), s.d);
        const Collapse east = collapse(s.e, s.ne + s.se, alive_c(I + 1, J), s.d);
        const float den = s.d - s.n - s.s - west.self - east.self;
        x0 = ratio(west.weight, den);
        x1 = ratio(east.weight, den);
      }
    }
    if (2 * J + 1 < F.h) {
      const size_t k = F.at(2 * I, 2 * J + 1);
      if (F.alive[k]) {
        const Stencil s = stencil_at(F, k);
        const Collapse north = collapse(s.n, s.nw + s.ne, alive_c(I, J), s.d);
        const Collapse south = collapse(s.s, s.sw + s.se, alive_c(I, J + 1), s.d);
        const float den = s.d - s.w - s.e - north.self - south.self;
        y0 = ratio(north.weight, den);
        y1 = ratio(south.weight, den);
      }
    }
    P.x0[kc] = x0;
    P.x1[kc] = x1;
    P.y0[kc] = y0;
    P.y1[kc] = y1;
  });
  copy_plain({&P.x0, &P.x1, &P.y0, &P.y1});
  const int cs = C.stride;
  cells([&](int I, int J, size_t kc) {
    float c00 = 0, c10 = 0, c01 = 0, c11 = 0;
    if (2 * I + 1 < F.w && 2 * J + 1 < F.h) {
      const size_t k = F.at(2 * I + 1, 2 * J + 1);
      if (F.alive[k]) {
        const Stencil s = stencil_at(F, k);
        const float inv = s.d > 1e-6f ? 1.0f / s.d : 0.0f;
        c00 = (s.w * P.y0[kc] + s.n * P.x0[kc] + s.nw * alive_c(I, J)) * inv;
        c10 = (s.e * P.y0[kc + 1] + s.n * P.x1[kc] + s.ne * alive_c(I + 1, J)) * inv;
        c01 = (s.w * P.y1[kc] + s.s * P.x0[kc + cs] + s.sw * alive_c(I, J + 1)) * inv;
        c11 = (s.e * P.y1[kc + 1] + s.s * P.x1[kc + cs] + s.se * alive_c(I + 1, J + 1)) * inv;
      }
    }
    P.c00[kc] = c00;
    P.c10[kc] = c10;
    P.c01[kc] = c01;
    P.c11[kc] = c11;
  });
  copy_plain({&P.c00, &P.c10, &P.c01, &P.c11});
}

// What the rows of A P of one fine row read (see ap_rows), as plain pointers.
struct ApInputs {
  const float* coeff;  // the row's stencils (ap_coefficients): coeff[m * lanes + I + 1]
  int lanes;
  const float *x0, *x1, *y0, *y1, *c00, *c10, *c01, *c11;  // Prolongation, by padded coarse index
  const std::uint8_t* alive;                               // the fine level's, by padded index
  // The fine row's, set per row: C.at(0, (y + dy) >> 1) and F.at(0, y + dy) for dy = -1, 0, 1.
  size_t cell_row[3] = {}, fine_row[3] = {};
};

// The stencils of the fine points x = 2I + PX of row y, lanes I in [i0, i1), as the rows of A
// that ap_rows multiplies: coeff[m * lanes + I + 1] for the nine points m = nw, n, ne, w, self, e,
// sw, s, se (couplings negated), all 0 where the point is not alive. The finest level's corners
// are not written: ap_rows does not read them there (they are 0).
template <int PX>
void ap_coefficients(const Level& F, int y, int i0, int i1, float* coeff, int lanes) {
  const int fs = F.stride;
  const size_t row = F.at(PX, y);
  const std::uint8_t* alive = F.alive.data();
  float* c[9];
  for (int m = 0; m < 9; ++m) c[m] = coeff + m * lanes + 1;
  // Every load is made (the arrays are padded), and only then selected: no branch, so that the
  // loops vectorise; ivdep: `coeff` overlaps none of the level's arrays.
  if (!F.code.empty()) {
    const std::uint8_t* code = F.code.data();
    const float* diag = F.diag.data();
#pragma GCC ivdep
    for (int I = i0; I < i1; ++I) {
      const size_t k = row + 2 * size_t(I);
      const std::uint8_t own = code[k], west = code[k - 1], north = code[k - fs];
      const bool a = alive[k];
      const float anchored = diag[k], links = kLinksDiag[own >> kCodeLinksShift];
      c[1][I] = a ? (north & kCodeSouth ? -1.0f : -0.0f) : 0.0f;
      c[3][I] = a ? (west & kCodeEast ? -1.0f : -0.0f) : 0.0f;
      c[4][I] = a ? (own & kCodeAnchored ? anchored : links) : 0.0f;
      c[5][I] = a ? (own & kCodeEast ? -1.0f : -0.0f) : 0.0f;
      c[7][I] = a ? (own & kCodeSouth ? -1.0f : -0.0f) : 0.0f;
    }
    return;
  }
  const float *diag = F.diag.data(), *ae = F.ae.data(), *as = F.as.data(), *ase = F.ase.data(),
              *asw = F.asw.data();
#pragma GCC ivdep
  for (int I = i0; I < i1; ++I) {
    const size_t k = row + 2 * size_t(I);
    // Times 0 or 1 rather than selected (a select of a load became a masked load, which does
    // not vectorise at a stride of 2): a dead point's coefficients may be -0 instead of +0, which
    // adds the same nothing to the sums.
    const float a = alive[k];
    c[0][I] = -ase[k - fs - 1] * a;
    c[1][I] = -as[k - fs] * a;
    c[2][I] = -asw[k - fs + 1] * a;
    c[3][I] = -ae[k - 1] * a;
    c[4][I] = diag[k] * a;
    c[5][I] = -ae[k] * a;
    c[6][I] = -asw[k] * a;
    c[7][I] = -as[k] * a;
    c[8][I] = -ase[k] * a;
  }
}

// One term of row p of A P (see ap_rows): the coefficient of p's neighbour q = p + (DX, DY)
// times q's row of P, whose at most four weights go to the corners of q's cell: which of them
// can be other than 0 follows from q's parity, and only those are added (a weight that is 0
// would add +-0, which leaves a sum that starts at +0 as it is). P's weights are 0 where their
// fine point is not alive or lies outside the level (build_prolongation writes them so, and the
// ghost cells stay 0), so only a coarse point itself needs its alive flag read.
template <int PX, int PY, int DX, int DY>
inline void ap_term(const ApInputs& in, int I, float (&o)[9]) {
  // q's cell column minus I, and the place of q's cell in p's 3x3 block of coarse points.
  constexpr int off = (PX + DX) >> 1;
  constexpr int ox = off - ((PX - 1) >> 1), oy = ((PY + DY) >> 1) - ((PY - 1) >> 1);
  constexpr bool odd_x = (PX + DX) & 1, odd_y = (PY + DY) & 1;
  const float c = in.coeff[((DY + 1) * 3 + DX + 1) * in.lanes + I + 1];
  const size_t kq = in.cell_row[DY + 1] + size_t(I + off);
  if constexpr (!odd_x && !odd_y) {
    // A coarse point itself: weight 1, or 0 where it is not alive.
    o[oy * 3 + ox] += c * (in.alive[in.fine_row[DY + 1] + 2 * size_t(I + off)] ? 1.0f : 0.0f);
  } else if constexpr (!odd_y) {
    o[oy * 3 + ox] += c * in.x0[kq];
    o[oy * 3 + ox + 1] += c * in.x1[kq];
  } else if constexpr (!odd_x) {
    o[oy * 3 + ox] += c * in.y0[kq];
    o[(oy + 1) * 3 + ox] += c * in.y1[kq];
  } else {
    o[oy * 3 + ox] += c * in.c00[kq];
    o[oy * 3 + ox + 1] += c * in.c10[kq];
    o[(oy + 1) * 3 + ox] += c * in.c01[kq];
    o[(oy + 1) * 3 + ox + 1] += c * in.c11[kq];
  }
}

// Rows p of A P for the fine points x = 2I + PX, lanes I in [i0, i1), of a fine row y of parity
// PY: out[m * lanes + I + 1] for the 3x3 block m of coarse points from base(p) = ((x-1)>>1,
// (y-1)>>1). Row p of A P is the sum over the stencil's points q of coeff(q) times the P row of
// q; the terms are added in the order of q (row by row), then of q's weights, each as one fused
// multiply-add into its coarse point's sum, which starts at +0. A point that is not alive has
// coefficients 0 and so a row of +0. One lane is one fine point, with no branch: the loop
// vectorises. The finest level's stencils have no corners (kNine false).
template <int PX, int PY, bool kNine>
void ap_rows(const ApInputs& inputs, int i0, int i1, float* out) {
  const ApInputs in = inputs;  // a local copy: its pointers are not reloaded in the loop
  // ivdep: `out` overlaps none of the inputs, so the lanes are independent.
#pragma GCC ivdep
  for (int I = i0; I < i1; ++I) {
    float o[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    if constexpr (kNine) ap_term<PX, PY, -1, -1>(in, I, o);
    ap_term<PX, PY, 0, -1>(in, I, o);
    if constexpr (kNine) ap_term<PX, PY, 1, -1>(in, I, o);
    ap_term<PX, PY, -1, 0>(in, I, o);
    ap_term<PX, PY, 0, 0>(in, I, o);
    ap_term<PX, PY, 1, 0>(in, I, o);
    if constexpr (kNine) ap_term<PX, PY, -1, 1>(in, I, o);
    ap_term<PX, PY, 0, 1>(in, I, o);
    if constexpr (kNine) ap_term<PX, PY, 1, 1>(in, I, o);
    for (int m = 0; m < 9; ++m) out[m * in.lanes + I + 1] = o[m];
  }
}

// ap_rows by the parities of x and y and the level's kind: kApRows[px | py << 1 | nine << 2].
using ApRowsFn = void (*)(const ApInputs&, int, int, float*);
constexpr ApRowsFn kApRows[8] = {ap_rows<0, 0, false>, ap_rows<1, 0, false>, ap_rows<0, 1, false>,
                                 ap_rows<1, 1, false>, ap_rows<0, 0, true>,  ap_rows<1, 0, true>,
                                 ap_rows<0, 1, true>,  ap_rows<1, 1, true>};

// The terms of the stored stencil of coarse point K, A_c(K, K + d) for d = self, east, south,
// south-east and south-west (m = 0..4): over the fine points p = (2I + ox, 2J + oy) around K, the
// weight of K in p's row of P times the entry of p's row of A P for K + d (`entry`, its place in
// the 3x3 block from base(p)), in the order the sums add them.
template <class Term>
[[gnu::always_inline]] inline void galerkin_terms(const Term& term) {
  constexpr int kDx[5] = {0, 1, 0, 1, -1}, kDy[5] = {0, 0, 1, 1, 1};
#pragma GCC unroll 3
  for (int oy = -1; oy <= 1; ++oy)
#pragma GCC unroll 3
    for (int ox = -1; ox <= 1; ++ox) {
      // K - base(p) is 1 for an offset of -1 or 0, and 0 for +1.
      const int sx0 = ox == 1 ? 0 : 1, sy0 = oy == 1 ? 0 : 1;
#pragma GCC unroll 5
      for (int m = 0; m < 5; ++m) {
        const int sx = sx0 + kDx[m], sy = sy0 + kDy[m];
        if (sx < 0 || sx > 2 || sy > 2) continue;
        term(oy, ox, m, sy * 3 + sx);
      }
    }
}

// The Galerkin coarse operator of level l+1, A_c = P^T (A P), one chunk of coarse rows at a time.
// Row p of P, for fine point p = (x,y) in cell (x>>1, y>>1), holds at most four weights: to the
// cell's corners (I,J), (I+1,J), (I,J+1), (I+1,J+1). Row p of A P then touches a 3x3 block of
// coarse points whose corner is base(p) = ((x-1)>>1, (y-1)>>1). Both products run a row at a
// time over arrays of lanes, one lane a column (the fine points of one parity of x, the coarse
// points of a row), so that they vectorise; each lane adds its terms in the order of the one-point
// formula, so the stencils have the bits that computing them point by point gives.
template <int NC>
std::vector<std::uint8_t> Multigrid<NC>::galerkin_product(int l,
                                                          const std::vector<std::uint8_t>* rebuild,
                                                          const PlainPoints& plain) {
  const Level& F = levels_[l];
  Level& C = levels_[l + 1];
  const size_t nc = C.padded();
  const int cs = C.stride;
  const Prolongation& P = prolong_[l];
  std::vector<std::uint8_t> changed;
  if (rebuild)
    changed.assign(nc, 0);
  else
    for (auto* v : {&C.diag, &C.inv_diag, &C.ae, &C.as, &C.ase, &C.asw})
      assign_touched(*v, nc, 0.0f);
  // Stores a coarse point's stencil (rebuilt points: noting which changed). Made in each task
  // with the arrays as its own values: a byte store may alias anything, and through references
  // every store read the arrays' places again.
  const auto stencil_store = [&] {
    return [arrays = std::array<float*, 6>{C.diag.data(), C.inv_diag.data(), C.ae.data(),
                                           C.as.data(), C.ase.data(), C.asw.data()},
            changes = rebuild ? changed.data() : nullptr](size_t kc, const float(&v)[6]) {
      bool c = false;
      for (int m = 0; m < 6; ++m) c |= update(arrays[m][kc], v[m]);
      if (changes) changes[kc] = c;
    };
  };
  // Lane I + 1 holds column I, from -1 (a column of zeros: no fine point x = -1) to C.w.
  const int lanes = C.w + 2;
  // The fine points of each parity of x: x = 2I + parity < F.w.
  const int columns[2] = {(F.w + 1) / 2, F.w / 2};
  for_rows(C.h, C.w * 32, [&](int J0, int J1) {
    // Plain coarse points (plain_points) are computed once, at the model.
    const std::uint8_t *const todo = plain.todo.data(), *const alive = C.alive.data();
    const int cw = C.w;
    // The columns with a point to compute in any of the task's rows.
    std::vector<std::uint8_t> row_wanted(size_t(J1 - J0), 0), column_wanted(size_t(cw), 0);
    for (int J = J0; J < J1; ++J) {
      const std::uint8_t* row = todo + C.at(0, J);
      for (int I = 0; I < cw; ++I) column_wanted[I] |= row[I] == PlainPoints::kCompute;
    }
    // Rows of A P of fine rows y_first .. y_first + y_count - 1 (those within 1 of a wanted coarse
    // row), each parity's lanes as columns.
    const int y_first = 2 * J0 - 1, y_count = 2 * (J1 - J0) + 1;
    const size_t row_floats = size_t(2) * 9 * lanes;
    std::unique_ptr<float[]> ap, coeff;
    const auto ap_at = [&](int y, int parity) {
      return &ap[size_t(y - y_first) * row_floats + size_t(parity) * 9 * lanes];
    };
    ApInputs in{nullptr,      lanes,        P.x0.data(),  P.x1.data(),  P.y0.data(),   P.y1.data(),
                P.c00.data(), P.c10.data(), P.c01.data(), P.c11.data(), F.alive.data()};
    // The wanted points of the columns [i_lo, i_hi), from the lanes i_lo - 1 .. i_hi - 1 of A P:
    // all that those coarse points read. Each lane's values are its own (no lane reads another's),
    // so computing some columns gives each the bits that computing all of them gives.
    const auto compute_columns = [&](int i_lo, int i_hi) {
      if (!ap) {  // the task's buffers, once it has a column to compute
        ap.reset(new float[size_t(y_count) * row_floats]);
        coeff.reset(new float[size_t(9) * lanes]);
        in.coeff = coeff.get();
      }
      const int a_lo = i_lo - 1, a_hi = i_hi;  // lanes read, as columns
      // The task's rows with a point to compute in these columns.
      for (int J = J0; J < J1; ++J) {
        const std::uint8_t* row = todo + C.at(0, J);
        row_wanted[J - J0] = 0;
        for (int I = i_lo; I < i_hi && !row_wanted[J - J0]; ++I)
          row_wanted[J - J0] = row[I] == PlainPoints::kCompute;
      }
      for (int y = y_first; y < y_first + y_count; ++y) {
        const int J = y >> 1;  // the wanted rows that read fine row y: J and, for odd y, J + 1
        const bool read = (J >= J0 && row_wanted[J - J0]) ||
                          ((y & 1) && J + 1 < J1 && J + 1 >= J0 && row_wanted[J + 1 - J0]);
        if (!read) continue;
        for (int dy = -1; dy <= 1; ++dy) {
          in.cell_row[dy + 1] = C.at(0, (y + dy) >> 1);
          in.fine_row[dy + 1] = F.at(0, y + dy);
        }
        for (int parity = 0; parity < 2; ++parity) {
          float* out = ap_at(y, parity);
          // Columns outside the level, and rows outside it, are rows of zeros.
          const int b_lo = std::max(a_lo, 0);
          const int b_hi = y < 0 || y >= F.h ? b_lo : std::min(a_hi, columns[parity]);
          const auto clear = [&](int from, int to) {
            for (int I = from; I < to; ++I)
              for (int m = 0; m < 9; ++m) out[m * lanes + I + 1] = 0.0f;
          };
          clear(a_lo, b_lo);
          clear(std::max(b_hi, b_lo), a_hi);
          if (b_lo >= b_hi) continue;
          (parity ? ap_coefficients<1> : ap_coefficients<0>)(F, y, b_lo, b_hi, coeff.get(), lanes);
          kApRows[parity | (y & 1) << 1 | F.nine_point << 2](in, b_lo, b_hi, out);
        }
      }
      // A_c(K, K + d) for d = self, east, south, south-east, south-west: sum over the nine fine
      // points p around K of P(p, K) * (A P)(p, K + d), in double, lanes of one coarse row.
      for (int J = J0; J < J1; ++J) {
        if (!row_wanted[J - J0]) continue;
        const size_t k0 = C.at(0, J);
        // (A P) of fine point (2I + ox, 2J + oy), entry m: rows[oy + 1][ox + 1][m * lanes + I].
        const float* rows[3][3];
        for (int oy = -1; oy <= 1; ++oy) {
          rows[oy + 1][0] = ap_at(2 * J + oy, 1);  // x = 2(I - 1) + 1: lane I - 1, at index I
          rows[oy + 1][1] = ap_at(2 * J + oy, 0) + 1;
          rows[oy + 1][2] = ap_at(2 * J + oy, 1) + 1;
        }
#if defined(__AVX512BW__) && defined(__AVX512VL__)
        // Eight points at a time, in double: each lane's terms in the scalar loop's order (the
        // products of two floats are exact in double, so fused multiply-adds give its bits), and
        // the stores and change flags of store(), masked to the points to compute. The scalar
        // loops below, a point at a time, were half of galerkin_product's own time.
        float* const arrays[6] = {C.diag.data(), C.inv_diag.data(), C.ae.data(),
                                  C.as.data(),   C.ase.data(),      C.asw.data()};
        std::uint8_t* const changes = rebuild ? changed.data() : nullptr;
        for (int I = i_lo; I < i_hi; I += 8) {
          const __mmask8 lanes8 = __mmask8(lanes_left(i_hi - I));
          const size_t kc = k0 + I;
          // The next row's stored stencils, a line of each array every sixteen points: their old
          // values are read for the change flags, and waited on memory (0.3-0.6 ms of a new
          // 1024^2 drawing's setup without this).
          if (((I - i_lo) & 15) == 0)
            for (float* a : arrays) prefetch(a, std::ptrdiff_t(kc + cs));
          const auto widen = [&](const float* q) {
            return _mm512_cvtps_pd(_mm256_maskz_loadu_ps(lanes8, q));
          };
          const __m512d weight[3][3] = {
              {widen(&in.c11[kc - cs - 1]), widen(&in.y1[kc - cs]), widen(&in.c01[kc - cs])},
              {widen(&in.x1[kc - 1]), _mm512_set1_pd(1.0), widen(&in.x0[kc])},
              {widen(&in.c10[kc - 1]), widen(&in.y0[kc]), widen(&in.c00[kc])}};
          __m512d acc[5];
          for (__m512d& a : acc) a = _mm512_setzero_pd();
          galerkin_terms([&](int oy, int ox, int m, int entry) {
            acc[m] = _mm512_fmadd_pd(weight[oy + 1][ox + 1],
                                     widen(rows[oy + 1][ox + 1] + I + entry * lanes), acc[m]);
          });
          const __mmask16 lanes16 = lanes8;
          const __mmask8 compute =
              __mmask8(_mm_mask_cmpeq_epi8_mask(lanes16, _mm_maskz_loadu_epi8(lanes16, todo + kc),
                                                _mm_set1_epi8(PlainPoints::kCompute)));
          if (!compute) continue;
          const __m128i live = _mm_maskz_loadu_epi8(compute, alive + kc);
          const __mmask8 alive8 = __mmask8(_mm_test_epi8_mask(live, live));
          const __m512d d = acc[0], sign = _mm512_set1_pd(-0.0);
          const __mmask8 positive = _mm512_cmp_pd_mask(d, _mm512_setzero_pd(), _CMP_GT_OQ);
          const __m256 value[6] = {
              _mm512_cvtpd_ps(d),
              _mm512_cvtpd_ps(_mm512_maskz_div_pd(positive, _mm512_set1_pd(1.0), d)),
              _mm512_cvtpd_ps(_mm512_xor_pd(acc[1], sign)),
              _mm512_cvtpd_ps(_mm512_xor_pd(acc[2], sign)),
              _mm512_cvtpd_ps(_mm512_xor_pd(acc[3], sign)),
              _mm512_cvtpd_ps(_mm512_xor_pd(acc[4], sign))};
          __mmask8 differs = 0;
          for (int m = 0; m < 6; ++m) {
            // (A point that is not alive: zeros, as store() writes them.)
            const __m256 v = _mm256_maskz_mov_ps(alive8, value[m]);
            const __m256 before = _mm256_maskz_loadu_ps(compute, arrays[m] + kc);
            differs |= _mm256_mask_cmpneq_epi32_mask(compute, _mm256_castps_si256(before),
                                                     _mm256_castps_si256(v));
            _mm256_mask_storeu_ps(arrays[m] + kc, compute, v);
          }
          if (changes) _mm_mask_storeu_epi8(changes + kc, compute, _mm_maskz_set1_epi8(differs, 1));
        }
#else
        const auto store = stencil_store();
        std::vector<double> sums(size_t(5) * lanes);
        double* s = sums.data();
        for (int I = i_lo; I < i_hi; ++I) {
          const size_t kc = k0 + I;
          // Weight of K in the P row of fine point (2I+ox, 2J+oy).
          const float weight[3][3] = {{in.c11[kc - cs - 1], in.y1[kc - cs], in.c01[kc - cs]},
                                      {in.x1[kc - 1], 1.0f, in.x0[kc]},
                                      {in.c10[kc - 1], in.y0[kc], in.c00[kc]}};
          double acc[5] = {0, 0, 0, 0, 0};
          galerkin_terms([&](int oy, int ox, int m, int entry) {
            acc[m] += double(weight[oy + 1][ox + 1]) * rows[oy + 1][ox + 1][I + entry * lanes];
          });
          for (int m = 0; m < 5; ++m) s[m * lanes + I] = acc[m];
        }
        for (int I = i_lo; I < i_hi; ++I) {
          const size_t kc = k0 + I;
          if (todo[kc] != PlainPoints::kCompute) continue;
          if (!alive[kc]) {
            if (rebuild) store(kc, {0, 0, 0, 0, 0, 0});
            continue;
          }
          const double d = s[I];
          store(kc, {float(d), d > 0 ? float(1.0 / d) : 0.0f, float(-s[lanes + I]),
                     float(-s[2 * lanes + I]), float(-s[3 * lanes + I]), float(-s[4 * lanes + I])});
        }
#endif
      }
    };
    // Runs of wanted columns, each computed on its own: the points to compute lie near the
    // curves, and one span from the first to the last of them computed most of a row for nothing.
    // Runs closer than kJoin columns are one (a run's fixed cost is its two edge lanes, and the
    // rows' set-up).
    constexpr int kJoin = 32;
    for (int I = 0; I < C.w;) {
      if (!column_wanted[I]) {
        ++I;
        continue;
      }
      int end = I + 1, gap = 0;
      for (int K = end; K < C.w && gap < kJoin; ++K) {
        if (column_wanted[K])
          end = K + 1, gap = 0;
        else
          ++gap;
      }
      compute_columns(I, end);
      I = end;
    }
  });
  if (!plain.model) return changed;
  const size_t model = *plain.model;
  const float stencil[6] = {C.diag[model], C.inv_diag[model], C.ae[model],
                            C.as[model],   C.ase[model],      C.asw[model]};
  for_rows(C.h, C.w, [&](int J0, int J1) {
    const auto store = stencil_store();
    const std::uint8_t* const todo = plain.todo.data();
    for (size_t kc = C.at(0, J0); kc < C.at(0, J1); ++kc)
      if (todo[kc] == PlainPoints::kCopy) store(kc, stencil);
  });
  return changed;
}

// Dense LDLT of the coarsest level's free points.
template <int NC>
void Multigrid<NC>::build_coarsest() {
  const Level& L = levels_.back();
  coarse_points_.clear();
  coarse_values_.clear();
  std::vector<int> index(L.padded(), -1);
  for (int y = 0; y < L.h; ++y)
    for (int x = 0; x < L.w; ++x)
      if (L.alive[L.at(x, y)]) {
        index[L.at(x, y)] = int(coarse_points_.size());
        coarse_points_.push_back(L.at(x, y));
        coarse_values_.push_back(L.vat(x, y));
      }
  const int m = int(coarse_points_.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m, m);
  const int s = L.stride;
  for (int r = 0; r < m; ++r) {
    const size_t k = coarse_points_[r];
    M(r, r) = diag_of(L, k);
    const auto couple = [&](size_t k2, float a) {
      if (index[k2] >= 0 && a != 0.0f) {
        M(r, index[k2]) -= a;
        M(index[k2], r) -= a;
      }
    };
    couple(k + 1, east_of(L, k));
    couple(k + s, south_of(L, k));
    if (L.nine_point) {
      couple(k + s + 1, L.ase[k]);
      couple(k + s - 1, L.asw[k]);
    }
  }
  if (m > 0) coarse_ldlt_.compute(M);
}

template <int NC>
void Multigrid<NC>::solve_coarsest() {
  Level& L = levels_.back();
  const size_t n = L.padded();
  const int m = int(coarse_points_.size());
  if (m == 0) return;
  for (int c = 0; c < NC; ++c) {
    Eigen::VectorXd b(m);
    for (int r = 0; r < m; ++r) b[r] = L.rhs[c * n + coarse_values_[r]];
    const Eigen::VectorXd x = coarse_ldlt_.solve(b);
    for (int r = 0; r < m; ++r) L.e[c * n + coarse_values_[r]] = float(x[r]);
  }
}

// The couplings of one row of a coarse (9-point) level to its eight neighbours, and
// sum_q a_pq e_q over them for every point of the row (vectorises: contiguous loads). (The
// finest level's come from its codes: finest_coefficients.)
struct RowCouplings {
  const float *ae, *aw, *as, *an, *ase, *anw, *asw, *ane;
  int stride;

  RowCouplings(const Level& L, size_t row)
      : ae(&L.ae[row]),
        aw(&L.ae[row - 1]),
        as(&L.as[row]),
        an(&L.as[row - L.stride]),
        ase(&L.ase[row]),
        anw(&L.ase[row - L.stride - 1]),
        asw(&L.asw[row]),
        ane(&L.asw[row - L.stride + 1]),
        stride(L.stride) {}

  void neighbour_sum(const float* __restrict e, float* __restrict out, int w) const {
    const int s = stride;
    const float* __restrict pe = ae, * __restrict pw = aw, * __restrict ps = as, * __restrict pn = an;
    for (int x = 0; x < w; ++x)
      out[x] = pe[x] * e[x + 1] + pw[x] * e[x - 1] + ps[x] * e[x + s] + pn[x] * e[x - s];
    const float* __restrict pse = ase, * __restrict pnw = anw, * __restrict psw = asw, * __restrict pne = ane;
    for (int x = 0; x < w; ++x)
      out[x] += pse[x] * e[x + s + 1] + pnw[x] * e[x - s - 1] + psw[x] * e[x + s - 1] +
                pne[x] * e[x - s + 1];
  }
};

// The same, one point at a time (builds without AVX-512).
struct Coefficients1 {
  float e, w, s, n, d;
};
inline Coefficients1 finest_coefficients(const Level& F, const HalfRow& r, int i, bool inverse) {
  const std::uint8_t here = F.pcode[r.own + i], west = F.pcode[r.other + i + r.half - 1],
                     north = F.pcode[r.own + i - F.stride];
  const float d = here & kCodeAnchored
                      ? (inverse ? F.pinv_diag : F.pdiag)[r.own + i]
                      : (inverse ? kLinksInverse : kLinksDiag)[here >> kCodeLinksShift];
  return {here & kCodeEast ? 1.0f : 0.0f, west & kCodeEast ? 1.0f : 0.0f,
          here & kCodeSouth ? 1.0f : 0.0f, north & kCodeSouth ? 1.0f : 0.0f, d};
}
// Its four neighbours' sum at point q of a half row, in RowCouplings::neighbour_sum's order: east
// and west from the other half's `o`, south and north from the rows around (stride s).
inline float finest_edge_sum(const Coefficients1& k, const float* q, const float* o, int west,
                             int east, int s) {
  return k.e * o[east] + k.w * o[west] + k.s * q[s] + k.n * q[-s];
}

#if defined(__AVX512BW__) && defined(__AVX512VL__)
// The stencil's sums at sixteen points, in the scalar loops' order: the four edge neighbours'
// (west and east at `west` and `east`, south and north a row of stride s beyond and before
// `centre`), and the four corner neighbours' of the 9-point levels (around channel row `ec`).
template <class Load>
inline __m512 edge_sum(__m512 pw, __m512 pe, __m512 ps, __m512 pn, const float* west,
                       const float* east, const float* centre, int s, const Load& load) {
  __m512 t = _mm512_mul_ps(pw, load(west));
  t = _mm512_fmadd_ps(pe, load(east), t);
  t = _mm512_fmadd_ps(ps, load(centre + s), t);
  return _mm512_fmadd_ps(pn, load(centre - s), t);
}
template <class Load>
inline __m512 corner_sum(__m512 pnw, __m512 pse, __m512 psw, __m512 pne, const float* ec, int s,
                         const Load& load) {
  __m512 u = _mm512_mul_ps(pnw, load(ec - s - 1));
  u = _mm512_fmadd_ps(pse, load(ec + s + 1), u);
  u = _mm512_fmadd_ps(psw, load(ec + s - 1), u);
  return _mm512_fmadd_ps(pne, load(ec - s + 1), u);
}
#endif

// The couplings of the row starting at `row` of a coarse level and its diagonal (or its inverse).
struct RowOperator {
  RowCouplings a;
  const float* d;
};
RowOperator row_operator(const Level& L, size_t row, bool inverse) {
  return {RowCouplings(L, row), &(inverse ? L.inv_diag : L.diag)[row]};
}

// Relaxes the points of half `half` of row y of the finest level (its points of that x parity;
// Level::odd): each becomes what its equation asks given its neighbours, every channel with the
// couplings decoded once. The sum has the order of RowCouplings::neighbour_sum.
template <int NC>
void Multigrid<NC>::relax_finest_row(Level& F, int y, int half) {
  const size_t n = F.padded();
  const int s = F.stride;
  const HalfRow r = half_row(F, y, half);
  const int west = r.half - 1, east = r.half;  // the neighbours' places in the other half
  float* __restrict e[NC];
  const float* __restrict across[NC];
  const float* __restrict b[NC];
  for (int c = 0; c < NC; ++c) {
    e[c] = &F.e[c * n + r.own];
    across[c] = &F.e[c * n + r.other];
    b[c] = &F.rhs[c * n + r.own];
  }
#if defined(__AVX512BW__) && defined(__AVX512VL__)
  // Sixteen points at a time, every lane one of this half's, with the scalar loop's operations in
  // its order (the compiler contracts them to the same fused multiply-adds): the same bits.
  for (int i = 0; i < r.count; i += 16) {
    const __mmask16 in = lanes_left(r.count - i);
    const auto load = [&](const float* q) { return _mm512_maskz_loadu_ps(in, q); };
    // (No prefetch: the hardware prefetcher follows the half rows; docs/performance.md.)
    const Coefficients16 k = finest_coefficients(F, r, i, in, true);
    for (int c = 0; c < NC; ++c) {
      float* q = e[c] + i;
      const float* o = across[c] + i;
      const __m512 t = edge_sum(k.w, k.e, k.s, k.n, o + west, o + east, q, s, load);
      _mm512_mask_storeu_ps(q, in, _mm512_mul_ps(_mm512_add_ps(load(b[c] + i), t), k.d));
    }
  }
#else
  for (int i = 0; i < r.count; ++i) {
    const Coefficients1 k = finest_coefficients(F, r, i, true);
    for (int c = 0; c < NC; ++c) {
      const float t = finest_edge_sum(k, e[c] + i, across[c] + i, west, east, s);
      e[c][i] = (b[c][i] + t) * k.d;
    }
  }
#endif
}

// Relaxes the points of row y of a coarse (9-point) level whose x has parity `x_parity` (all
// channels): each becomes what its equation asks given its neighbours, every channel with the
// couplings loaded once; the sum has the order of RowCouplings::neighbour_sum. Point by point:
// relax_row_pair's path without AVX-512.
template <int NC>
void Multigrid<NC>::relax_row(Level& L, int y, int x_parity) {
  const size_t n = L.padded(), row = L.at(0, y);
  const int s = L.stride;
  float* __restrict e[NC];
  const float* __restrict b[NC];
  for (int c = 0; c < NC; ++c) {
    e[c] = &L.e[c * n + row];
    b[c] = &L.rhs[c * n + row];
  }
  const RowOperator op = row_operator(L, row, true);
  const RowCouplings& a = op.a;
  const float* __restrict id = op.d;
  for (int x = x_parity; x < L.w; x += 2) {
    const float pe = a.ae[x], pw = a.aw[x], ps = a.as[x], pn = a.an[x], d = id[x];
    const float pse = a.ase[x], pnw = a.anw[x], psw = a.asw[x], pne = a.ane[x];
    for (int c = 0; c < NC; ++c) {
      const float* ec = e[c];
      float t = pe * ec[x + 1] + pw * ec[x - 1] + ps * ec[x + s] + pn * ec[x - s];
      t += pse * ec[x + s + 1] + pnw * ec[x - s - 1] + psw * ec[x + s - 1] + pne * ec[x - s + 1];
      e[c][x] = (b[c][x] + t) * d;
    }
  }
}

// Row y of a 9-point level relaxed at parity `first`, then at the other parity: what
// relax_row(L, y, first) and relax_row(L, y, 1 - first) compute, to the bit. The AVX-512 path does
// both in one pass over the row, a block of sixteen points behind: block i's first parity, then
// block i-1's second, whose west and east neighbours (of the first parity) are the values just
// computed, taken from registers (no load waits for a store), and the same sixteen points'
// diagonal-neighbour sum (rows y-1 and y+1, which neither parity changes) computed once for both.
// Each point's operations are relax_row's in its order.
template <int NC>
void Multigrid<NC>::relax_row_pair(Level& L, int y, int first) {
#if defined(__AVX512BW__) && defined(__AVX512VL__)
  const size_t n = L.padded(), row = L.at(0, y);
  const int s = L.stride, w = L.w;
  float* __restrict e[NC];
  const float* __restrict b[NC];
  for (int c = 0; c < NC; ++c) {
    e[c] = &L.e[c * n + row];
    b[c] = &L.rhs[c * n + row];
  }
  const RowCouplings a(L, row);
  const float* id = &L.inv_diag[row];
  const __mmask16 second = first ? 0x5555 : 0xAAAA;
  // Per channel: the first parity's values of the block before (`last`) and of the one before
  // that (`before`; its lane 15 is the west neighbour of the block's lane 0), and the block
  // before's diagonal-neighbour sum. Outside the row: the ghost values.
  __m512 last[NC], before[NC], u_last[NC];
  for (int c = 0; c < NC; ++c) {
    last[c] = _mm512_set1_ps(e[c][-1]);
    before[c] = last[c];
    u_last[c] = _mm512_setzero_ps();
  }
  for (int x = 0; x < w + 16; x += 16) {
    __m512 now[NC], u_now[NC];
    if (x < w) {
      // The first parity of block x, as relax_row computes it (every lane; the first parity's
      // lanes are kept).
      const __mmask16 in = lanes_left(w - x);
      const auto load = [&](const float* q) { return _mm512_maskz_loadu_ps(in, q + x); };
      // The rows that the next row's relaxation reads first.
      for (const float* q : {a.ae, a.as, a.ase, a.asw, id}) prefetch(q, s + x);
      for (int c = 0; c < NC; ++c) prefetch(e[c], 2 * s + x), prefetch(b[c], s + x);
      const __m512 pe = load(a.ae), pw = load(a.aw), ps = load(a.as), pn = load(a.an), d = load(id);
      const __m512 pse = load(a.ase), pnw = load(a.anw), psw = load(a.asw), pne = load(a.ane);
      for (int c = 0; c < NC; ++c) {
        const float* ec = e[c];
        __m512 t = edge_sum(pw, pe, ps, pn, ec - 1, ec + 1, ec, s, load);
        const __m512 u = corner_sum(pnw, pse, psw, pne, ec, s, load);
        u_now[c] = u;
        t = _mm512_add_ps(t, u);
        // Lanes outside the row: the ghost value (lane w - x is the east neighbour of w - 1).
        now[c] = _mm512_mask_mov_ps(_mm512_set1_ps(ec[w]), in,
                                    _mm512_mul_ps(_mm512_add_ps(load(b[c]), t), d));
      }
    } else {
      for (int c = 0; c < NC; ++c) now[c] = _mm512_set1_ps(e[c][w]), u_now[c] = _mm512_setzero_ps();
    }
    if (x > 0) {
      // The second parity of block x - 16: its west and east neighbours are of the first parity,
      // in `last` and its neighbours in registers. Stored with the block's first parity.
      const int xb = x - 16;
      const __mmask16 in = lanes_left(w - xb);
      const auto load = [&](const float* q) { return _mm512_maskz_loadu_ps(in, q + xb); };
      const __m512 pe = load(a.ae), pw = load(a.aw), ps = load(a.as), pn = load(a.an), d = load(id);
      for (int c = 0; c < NC; ++c) {
        const float* ec = e[c];
        const __m512 west = _mm512_castsi512_ps(
            _mm512_alignr_epi32(_mm512_castps_si512(last[c]), _mm512_castps_si512(before[c]), 15));
        const __m512 east = _mm512_castsi512_ps(
            _mm512_alignr_epi32(_mm512_castps_si512(now[c]), _mm512_castps_si512(last[c]), 1));
        __m512 t = _mm512_mul_ps(pw, west);
        t = _mm512_fmadd_ps(pe, east, t);
        t = _mm512_fmadd_ps(ps, load(ec + s), t);
        t = _mm512_fmadd_ps(pn, load(ec - s), t);
        t = _mm512_add_ps(t, u_last[c]);
        const __m512 r = _mm512_mul_ps(_mm512_add_ps(load(b[c]), t), d);
        _mm512_mask_storeu_ps(e[c] + xb, in, _mm512_mask_mov_ps(last[c], second, r));
      }
    }
    for (int c = 0; c < NC; ++c) {
      before[c] = last[c];
      last[c] = now[c];
      u_last[c] = u_now[c];
    }
  }
#else
  relax_row(L, y, first);
  relax_row(L, y, 1 - first);
#endif
}

// Gauss-Seidel in an order-independent colouring: red-black on the 5-point finest level, four
// colours (x parity, y parity) on the 9-point levels. Each sweep has two stages, A and B:
// red then black, or even rows (colours 0, 1) then odd rows (colours 2, 3); reversed for
// post-smoothing so that the cycle is symmetric. Stage k of the sequence A1 B1 A2 B2 ... at row
// y needs stage k-1 at rows y-1..y+1 only (and nothing else reads what it overwrites), so one
// pass over memory does every stage of every sweep, a wave down the rows: stage 0 at row t,
// stage 1 at row t-1, stage 2 at row t-2, ... while those rows are in cache. Rows are split in
// chunks run in parallel; a chunk does stage k on its rows but the k nearest each neighbour
// chunk, which a second phase does around each chunk boundary, stage by stage. The result is
// exactly that of the plain colour-by-colour order, whatever the chunks. `row_done` runs one row
// behind the last stage (row y once the last stage has done row y+1), and around each chunk
// boundary after the second phase.
template <int NC>
void Multigrid<NC>::smooth(int l, int sweeps, bool reverse, const RowHook* row_done,
                           const RowHook* row_first) {
  Level& L = levels_[l];
  const int stages = 2 * sweeps;
  const auto stage = [&](int y, int k) {
    const bool first = k % 2 == 0;
    if (!L.nine_point) {
      const int colour = first != reverse ? 0 : 1;
      relax_finest_row(L, y, (colour + y) & 1);
      return;
    }
    const bool first_rows = reverse ? (y & 1) : !(y & 1);
    if (first_rows != first) return;
    relax_row_pair(L, y, reverse ? 1 : 0);
  };
  if (stages == 0) {
    if (row_first)
      for_rows(L.h, L.w * NC, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) (*row_first)(y);
      });
    if (row_done)
      for_rows(L.h, L.w * NC, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) (*row_done)(y);
      });
    return;
  }
  // Chunks: one to four per worker thread, the same number for each (3 chunks on two threads
  // left one idle for a third of the wave), of kPointsPerChunk points or more where there are
  // enough, and at least 4 rows per stage. No more: each chunk boundary leaves stages (stages - 1)
  // row-stages to the second phase, after a barrier and out of cache. At 1024^2 the finest
  // level's waves had 64 chunks, a fifth of their work in the second phase; with 8 (two threads)
  // its share of a new drawing's cycles fell from 16-17 to 14 ms.
  constexpr int kPointsPerChunk = 16384;
  const int threads = tbb::this_task_arena::max_concurrency();
  const int chunks =
      std::clamp(threads * std::clamp(L.w * L.h * NC / (threads * kPointsPerChunk), 1, 4), 1,
                 std::max(1, L.h / (4 * stages)));
  const auto first_row = [&](int c) { return int(int64_t(L.h) * c / chunks); };
  const auto parallel = [&](int first, int last, const auto& body) {
    if (last - first == 1)
      body(first);
    else if (last > first)
      tbb::parallel_for(first, last, body);
  };
  const int last = stages - 1;
  // row_first: the two rows around each chunk boundary first (both chunks' first stage reads
  // them), the other rows by their chunk one row ahead of its first stage.
  if (row_first)
    parallel(1, chunks, [&](int c) {
      (*row_first)(first_row(c) - 1);
      (*row_first)(first_row(c));
    });
  parallel(0, chunks, [&](int c) {
    const int y0 = first_row(c), y1 = first_row(c + 1);
    const int own0 = c == 0 ? 0 : y0 + 1, own1 = c + 1 == chunks ? L.h : y1 - 1;
    if (row_first && own0 == 0 && own1 > 0) (*row_first)(0);
    // The rows whose neighbourhood this phase finishes: the last stage's rows but the one
    // nearest each neighbour chunk.
    const int done0 = c == 0 ? 0 : y0 + last + 1, done1 = c + 1 == chunks ? L.h : y1 - last - 1;
    for (int t = y0; t < y1 + stages; ++t) {
      if (row_first && t + 1 >= own0 && t + 1 < own1) (*row_first)(t + 1);
      for (int k = 0; k < stages; ++k) {
        const int y = t - k;
        if (y >= (c == 0 ? 0 : y0 + k) && y < (c + 1 == chunks ? L.h : y1 - k)) stage(y, k);
      }
      const int y = t - last - 1;
      if (row_done && y >= done0 && y < done1) (*row_done)(y);
    }
  });
  parallel(1, chunks, [&](int c) {
    const int b = first_row(c);
    for (int k = 1; k < stages; ++k)
      for (int y = std::max(0, b - k); y < std::min(L.h, b + k); ++y) stage(y, k);
    if (row_done)
      for (int y = std::max(0, b - last - 1); y < std::min(L.h, b + last + 1); ++y) (*row_done)(y);
  });
}

// Row y of out = b - A e on level l (b == nullptr: out = -A e), every channel: out[c] points at
// the row's first point. With `norms`, the squared 2-norm of each channel's row (in float).
template <int NC>
void Multigrid<NC>::residual_row(int l, int y, const Plane* b_planes, const Plane& e_planes,
                                 float* const out[NC], float* norms) const {
  const Level& L = levels_[l];
  const size_t n = L.padded(), row = L.at(0, y);
  const int w = L.w;
  if (L.odd) {
    // The finest level, a half row at a time (Level::odd), its codes decoded into registers;
    // `out` holds the row in the values' layout. The operations of the loops below, in their
    // order (the same bits as in order). A e is taken as its couplings' differences,
    // sum a (e_c - e_nb), plus what the diagonal has beyond the couplings (the links to fixed
    // pixels, an anchor) times e_c: neighbours of a smooth e are close, so their differences are
    // exact in float32. As d e_c - sum a e_nb, every pixel's residual carried a rounding error of
    // e's own size (about 1e-7), which A^-1 amplifies by the square of a region's size: the
    // cycles' answer stalled 0.34/255 from the exact one on a 1024^2 drawing (bubble.xml), above
    // the 8-bit stopping rule's bound, and now goes below it.
    const int s = L.stride;
    for (int half = 0; half < 2; ++half) {
      const HalfRow r = half_row(L, y, half);
      const int west = r.half - 1, east = r.half, to = int(r.own - row);
#if defined(__AVX512BW__) && defined(__AVX512VL__)
      for (int i = 0; i < r.count; i += 16) {
        const __mmask16 in = lanes_left(r.count - i);
        const auto load = [&](const float* q) { return _mm512_maskz_loadu_ps(in, q); };
        const Coefficients16 k = finest_coefficients(L, r, i, in, false);
        const __m512 rest =
            _mm512_sub_ps(k.d, _mm512_add_ps(_mm512_add_ps(k.w, k.e), _mm512_add_ps(k.s, k.n)));
        for (int c = 0; c < NC; ++c) {
          const float *q = &e_planes[c * n + r.own + i], *o = &e_planes[c * n + r.other + i];
          const __m512 ec = load(q);
          // sum a (e_nb - e_c), in edge_sum's order
          __m512 t = _mm512_mul_ps(k.w, _mm512_sub_ps(load(o + west), ec));
          t = _mm512_fmadd_ps(k.e, _mm512_sub_ps(load(o + east), ec), t);
          t = _mm512_fmadd_ps(k.s, _mm512_sub_ps(load(q + s), ec), t);
          t = _mm512_fmadd_ps(k.n, _mm512_sub_ps(load(q - s), ec), t);
          const __m512 v =
              b_planes ? _mm512_add_ps(
                             _mm512_fnmadd_ps(rest, ec, load(&(*b_planes)[c * n + r.own + i])), t)
                       : _mm512_fnmadd_ps(rest, ec, t);
          _mm512_mask_storeu_ps(out[c] + to + i, in, v);
        }
      }
#else
      for (int i = 0; i < r.count; ++i) {
        const Coefficients1 k = finest_coefficients(L, r, i, false);
        const float rest = k.d - ((k.w + k.e) + (k.s + k.n));
        for (int c = 0; c < NC; ++c) {
          const float *q = &e_planes[c * n + r.own + i], *o = &e_planes[c * n + r.other + i];
          const float ec = q[0];
          const float t =
              k.w * (o[west] - ec) + k.e * (o[east] - ec) + k.s * (q[s] - ec) + k.n * (q[-s] - ec);
          out[c][to + i] =
              b_planes ? t + ((*b_planes)[c * n + r.own + i] - rest * ec) : t - rest * ec;
        }
      }
#endif
    }
  } else {
    const RowOperator op = row_operator(L, row, false);
    const float* __restrict d = op.d;
    for (int c = 0; c < NC; ++c) {
      const float* __restrict e = &e_planes[c * n + row];
      float* __restrict r = out[c];
      op.a.neighbour_sum(e, r, w);
      if (b_planes) {
        const float* __restrict b = &(*b_planes)[c * n + row];
        for (int x = 0; x < w; ++x) r[x] += b[x] - d[x] * e[x];
      } else {
        for (int x = 0; x < w; ++x) r[x] -= d[x] * e[x];
      }
    }
  }
  if (norms)  // while the row is in cache
    for (int c = 0; c < NC; ++c) {
      float sum = 0;
      for (const Level::Run& run : L.runs()) {
        const float* __restrict r = out[c] + run.offset;
#pragma omp simd reduction(+ : sum)
        for (int i = 0; i < run.count; ++i) sum += r[i] * r[i];
      }
      norms[c] = sum;
    }
}

// out = b - A e on level l (b == nullptr: out = -A e). Arrays are channel planes, padded. Without
// `out` only the row norms are computed, a row at a time.
template <int NC>
void Multigrid<NC>::residual_of(int l, const Plane* b_planes, const Plane& e_planes, Plane* out,
                                std::vector<double>* row_norms) const {
  const Level& L = levels_[l];
  const size_t n = L.padded();
  for_rows(L.h, L.w * NC, [&](int y0, int y1) {
    std::vector<float> buffer(out ? 0 : size_t(L.stride) * NC);  // rows laid out as the level's
    for (int y = y0; y < y1; ++y) {
      float* rows[NC];
      for (int c = 0; c < NC; ++c)
        rows[c] = out ? &(*out)[c * n + L.at(0, y)] : &buffer[size_t(c) * L.stride];
      float norms[NC];
      residual_row(l, y, b_planes, e_planes, rows, row_norms ? norms : nullptr);
      if (row_norms)
        for (int c = 0; c < NC; ++c) (*row_norms)[size_t(y) * NC + c] = norms[c];
    }
  });
}

// 2-norms of the residual per channel; rows are summed in order, whatever the thread count.
template <int NC>
std::array<double, NC> Multigrid<NC>::residual_norms(int l) const {
  const Level& L = levels_[l];
  std::vector<double> rows(size_t(L.h) * NC, 0.0);
  residual_of(l, &L.rhs, L.e, nullptr, &rows);
  return sum_row_norms(rows, L.h);
}

// The 2-norms per channel from the squared norms of each row (`rows`: h rows of NC), in order.
template <int NC>
std::array<double, NC> Multigrid<NC>::sum_row_norms(const std::vector<double>& rows, int h) const {
  std::array<double, NC> norms{};
  for (int y = 0; y < h; ++y)
    for (int c = 0; c < NC; ++c) norms[c] += rows[size_t(y) * NC + c];
  for (double& v : norms) v = std::sqrt(v);
  return norms;
}

template <int NC>
void Multigrid<NC>::restrict_row(int l, int J, const float* const north[NC],
                                 const float* const centre[NC], const float* const south[NC]) {
  Level& C = levels_[l + 1];
  const Prolongation& P = prolong_[l];
  const size_t nc = C.padded();
  const int cs = C.stride;
  // Where a fine row's odd points start, from its x = 0 (0: the row is in order).
  const int odd_at = levels_[l].odd ? levels_[l].odd - Level::kLeft : 0;
#if defined(__AVX512BW__) && defined(__AVX512VL__)
  // Sixteen coarse points at a time: the fine rows' even and odd points loaded apart (or gathered
  // from 32 in registers), and the sum below term by term in its order (the compiler contracts
  // it to the same chain of fused multiply-adds).
  const int fw = levels_[l].w;  // fine rows are readable from x = -1 to fw
  for (int I = 0; I < C.w; I += 16) {
    const size_t kc = C.at(I, J);
    const __mmask16 in = lanes_left(C.w - I);
    const auto load = [&](const Plane& v, size_t k) { return _mm512_maskz_loadu_ps(in, &v[k]); };
    const auto load_at = [&](const float* q) { return _mm512_maskz_loadu_ps(in, q); };
    for (const Plane* q : {&P.x0, &P.x1, &P.y0, &P.y1, &P.c00, &P.c10, &P.c01, &P.c11})
      prefetch(q->data(), kc + cs);  // the next coarse row's
    const __m512 x0 = load(P.x0, kc), x1 = load(P.x1, kc - 1), y0 = load(P.y0, kc),
                 y1 = load(P.y1, kc - cs), c00 = load(P.c00, kc), c10 = load(P.c10, kc - 1),
                 c01 = load(P.c01, kc - cs), c11 = load(P.c11, kc - cs - 1);
    const __mmask16 alive =
        _mm_test_epi8_mask(_mm_maskz_loadu_epi8(in, &C.alive[kc]), _mm_set1_epi8(1));
    const int x = 2 * I;
    // Fine points x + 2i + offset, i = 0..15, of a row (offset -1, 0 or 1): on the finest level
    // sixteen of one half of the row (Level::odd), elsewhere every other one in order.
    const auto fine = [&](const float* r, int offset) {
      if (odd_at) return load_at(r + (offset == 0 ? I : odd_at + I + (offset - 1) / 2));
      return every_other(r, x + offset, fw);
    };
    for (int c = 0; c < NC; ++c) {
      const float *rn = north[c], *r0 = centre[c], *rs = south[c];
      __m512 v = _mm512_fmadd_ps(x0, fine(r0, 1), fine(r0, 0));
      v = _mm512_fmadd_ps(x1, fine(r0, -1), v);
      v = _mm512_fmadd_ps(y0, fine(rs, 0), v);
      v = _mm512_fmadd_ps(y1, fine(rn, 0), v);
      v = _mm512_fmadd_ps(c00, fine(rs, 1), v);
      v = _mm512_fmadd_ps(c10, fine(rs, -1), v);
      v = _mm512_fmadd_ps(c01, fine(rn, 1), v);
      v = _mm512_fmadd_ps(c11, fine(rn, -1), v);
      _mm512_mask_storeu_ps(&C.rhs[c * nc + kc], in, _mm512_maskz_mov_ps(alive, v));
    }
  }
  return;
#endif
  // Fine point x of a row, for x in [-1, w].
  const auto at = [&](int x) { return odd_at ? (x & 1 ? odd_at : 0) + (x >> 1) : x; };
  for (int I = 0; I < C.w; ++I) {
    const size_t kc = C.at(I, J);
    const int x = at(2 * I), east = at(2 * I + 1), west = at(2 * I - 1);
    for (int c = 0; c < NC; ++c) {
      const float *rn = north[c], *r0 = centre[c], *rs = south[c];
      float v = 0.0f;
      if (C.alive[kc])
        v = r0[x] + P.x0[kc] * r0[east] + P.x1[kc - 1] * r0[west] + P.y0[kc] * rs[x] +
            P.y1[kc - cs] * rn[x] + P.c00[kc] * rs[east] + P.c10[kc - 1] * rs[west] +
            P.c01[kc - cs] * rn[east] + P.c11[kc - cs - 1] * rn[west];
      C.rhs[c * nc + kc] = v;
    }
  }
}

template <int NC>
void Multigrid<NC>::restrict_rhs_row(int l, int J) {
  const Level& L = levels_[l];
  const float *north[NC], *centre[NC], *south[NC];  // ghost rows beyond the level: 0
  for (int c = 0; c < NC; ++c) {
    north[c] = &L.rhs[c * L.padded() + L.vat(0, 2 * J - 1)];
    centre[c] = &L.rhs[c * L.padded() + L.vat(0, 2 * J)];
    south[c] = &L.rhs[c * L.padded() + L.vat(0, 2 * J + 1)];
  }
  restrict_row(l, J, north, centre, south);
}

// A cell (two fine points) at a time, so that the loops have no branch and vectorise; the sums
// are the same, term by term, as point by point. With kSet the row's values are replaced by
// 0 + P e_c, the bits of adding to a row of zeros (0 + -0 is +0), without the zeros' pass; with
// kFrom by from + P e_c, the bits of adding to e when it held `from`.
template <int NC>
template <Prolong kMode>
void Multigrid<NC>::prolongate_row(int l, int y, const Plane* from) {
  Level& F = levels_[l];
  const Level& C = levels_[l + 1];
  const Prolongation& P = prolong_[l];
  const size_t nf = F.padded(), nc = C.padded();
  const int cs = C.stride, pairs = F.w / 2;
  const size_t row = C.at(0, y >> 1);  // coarse cell (I, J) at row + I
  // The weights that the fine row two below reads (the next coarse row's).
  const auto ahead = [&](const Plane& v) {
    for (int I = 0; I <= pairs; I += 16) prefetch(v.data(), row + cs + I);
  };
  if (y & 1) {
    for (const Plane* v : {&P.y0, &P.y1, &P.c00, &P.c10, &P.c01, &P.c11}) ahead(*v);
  } else {
    ahead(P.x0), ahead(P.x1);
  }
  // The fine row's even points at even[k * I], its odd ones at odd[k * I]: k = 1 on the finest
  // level (two halves, Level::odd), 2 elsewhere (in order). Point i of the row becomes
  // was(i) + v: e's value there (kAdd), +0 (kSet) or from's value (kFrom).
  const auto add = [&](auto step) {
    constexpr int k = decltype(step)::value;
    for (int c = 0; c < NC; ++c) {
      float* __restrict even = &F.e[c * nf + F.vat(0, y)];
      float* __restrict odd = &F.e[c * nf + F.vat(1, y)];
      // (kFrom: `from` is another plane, so its rows overlap none of e's.)
      const float* __restrict from_even =
          kMode == Prolong::kFrom ? &(*from)[c * nf + F.vat(0, y)] : nullptr;
      const float* __restrict from_odd =
          kMode == Prolong::kFrom ? &(*from)[c * nf + F.vat(1, y)] : nullptr;
      const auto put = [&](float* q, const float* source, int i, float v) {
        if constexpr (kMode == Prolong::kSet)
          q[i] = 0.0f + v;
        else if constexpr (kMode == Prolong::kFrom)
          q[i] = source[i] + v;
        else
          q[i] = q[i] + v;
      };
      const float* __restrict ec = &C.e[c * nc + row];
      if (!(y & 1)) {
        const float* __restrict x0 = &P.x0[row], * __restrict x1 = &P.x1[row];
#pragma GCC ivdep
        for (int I = 0; I < pairs; ++I) {
          put(even, from_even, k * I, ec[I]);
          put(odd, from_odd, k * I, x0[I] * ec[I] + x1[I] * ec[I + 1]);
        }
        if (F.w & 1) put(even, from_even, k * pairs, ec[pairs]);
      } else {
        const float* __restrict es = ec + cs;
        const float* __restrict py0 = &P.y0[row], * __restrict py1 = &P.y1[row];
        const float* __restrict c00 = &P.c00[row], * __restrict c10 = &P.c10[row];
        const float* __restrict c01 = &P.c01[row], * __restrict c11 = &P.c11[row];
#pragma GCC ivdep
        for (int I = 0; I < pairs; ++I) {
          put(even, from_even, k * I, py0[I] * ec[I] + py1[I] * es[I]);
          put(odd, from_odd, k * I,
              c00[I] * ec[I] + c10[I] * ec[I + 1] + c01[I] * es[I] + c11[I] * es[I + 1]);
        }
        if (F.w & 1)
          put(even, from_even, k * pairs, py0[pairs] * ec[pairs] + py1[pairs] * es[pairs]);
      }
    }
  };
  if (F.odd)
    add(std::integral_constant<int, 1>{});
  else
    add(std::integral_constant<int, 2>{});
}

// The residual is restricted inside a smoothing's wave: each residual row is computed once its
// neighbourhood is final, while it is in cache, into a ring of the last three rows of the
// thread, and coarse row J is restricted by whichever thread completes the last of fine rows
// 2J-1 .. 2J+1 (from its ring, computing what it lacks: near chunk boundaries). The ring's rows
// are labelled with the wave's number, unique in the process (a thread's ring outlives the
// solve, and threads may run chunks of other solves in between), so no row of another wave is
// ever taken for one of this one.
template <int NC>
RowHook Multigrid<NC>::restricting(int l, RestrictWhenReady& ready, const MeasureHook* measure) {
  const Level& F = levels_[l];
  const int fs = F.stride;
  static std::atomic<std::uint64_t> waves{0};
  struct Ring {
    Plane rows;  // 3 slots of NC rows, each laid out as a level's
    std::uint64_t pass[3] = {0, 0, 0};
    int y[3] = {-1, -1, -1};
  };
  const std::uint64_t pass = ++waves;
  return RowHook([this, &ready, &F, fs, l, pass, m = measure](int y) {
    thread_local Ring ring;
    thread_local std::vector<float> zeros;
    if (ring.rows.size() < size_t(3) * NC * fs) {
      // The rows go with the old storage, and so do their labels: a larger solve run
      // alongside (a task of it taken between two of this pass) must not leave a slot that
      // claims a row of this pass and holds zeros.
      ring = Ring{};
      ring.rows.assign(size_t(3) * NC * fs, 0.0f);
    }
    if (zeros.size() < size_t(fs)) zeros.assign(size_t(fs), 0.0f);
    // Residual row `row` in the ring (x = 0 of each channel's row), computed unless it is
    // there; with `norms`, always computed (the row_done of its own row: not there yet).
    const auto residual = [&](int row, const float* out[NC], float* norms) {
      if (row < 0 || row >= F.h) {
        for (int c = 0; c < NC; ++c) out[c] = zeros.data() + Level::kLeft;
        return;
      }
      const int slot = row % 3;
      float* rows[NC];
      for (int c = 0; c < NC; ++c)
        out[c] = rows[c] = &ring.rows[(size_t(slot) * NC + c) * fs] + Level::kLeft;
      if (!norms && ring.pass[slot] == pass && ring.y[slot] == row) return;
      for (int c = 0; c < NC; ++c)
        for (int g : F.ghosts()) rows[c][g] = 0.0f;  // a level's row's ghosts
      residual_row(l, row, &F.rhs, F.e, rows, norms);
      ring.pass[slot] = pass;
      ring.y[slot] = row;
    };
    const float* unused[NC];
    float norms[NC];
    residual(y, unused, m ? norms : nullptr);
    if (m) (*m)(y, norms);
    ready.row_done(y, [&](int J) {
      const float *north[NC], *centre[NC], *south[NC];
      residual(2 * J - 1, north, nullptr);
      residual(2 * J, centre, nullptr);
      residual(2 * J + 1, south, nullptr);
      restrict_row(l, J, north, centre, south);
    });
  });
}

template <int NC>
void Multigrid<NC>::restrict_residual(int l) {
  RestrictWhenReady ready(levels_[l].h, levels_[l + 1].h);
  const RowHook restrict_rows = restricting(l, ready, nullptr);
  smooth(l, 0, false, &restrict_rows);
}

template <int NC>
void Multigrid<NC>::vcycle(int l, const MeasureHook* measure, CycleStart start, Plane* before,
                           bool last) {
  Level& F = levels_[l];
  // Where the cycle changes e before its post-smoothing, `before` is a copy (the coarsest level,
  // a pre-smoothing); elsewhere the post-smoothing's prolongation writes e from it.
  if (before && (l + 1 == int(levels_.size()) || start != CycleStart::kRestricted))
    std::copy(F.e.begin(), F.e.end(), before->begin());
  if (l + 1 == int(levels_.size())) {
    const auto t0 = Clock::now();
    if (start == CycleStart::kZero) fill_zero(F.e);  // (its points that are not free stay 0)
    solve_coarsest();
    level_ms_[l] += ms_since(t0);
    if (measure) {  // (a problem of one level)
      std::vector<float> buffer(size_t(F.stride) * NC);
      float* out[NC];
      for (int c = 0; c < NC; ++c) out[c] = &buffer[size_t(c) * F.stride];
      for (int y = 0; y < F.h; ++y) {
        float norms[NC];
        residual_row(l, y, &F.rhs, F.e, out, norms);
        (*measure)(y, norms);
      }
    }
    return;
  }
  const Level& C = levels_[l + 1];
  // Levels 2 and coarser are smoothed more (SolverOptions::coarse_smooth): they are cheap.
  const bool coarse = l >= 2;
  auto t0 = Clock::now();
  if (start != CycleStart::kRestricted) {
    RestrictWhenReady ready(F.h, C.h);
    const RowHook restrict_rows = restricting(l, ready, nullptr);
    const RowHook interpolate = [&](int y) { prolongate_row<Prolong::kSet>(l, y); };
    const RowHook zeros = [&](int y) { zero_row(F, y); };
    smooth(l, coarse ? options_.coarse_smooth : options_.pre_smooth, false, &restrict_rows,
           start == CycleStart::kFromCoarse ? &interpolate
           : start == CycleStart::kZero     ? &zeros
                                            : nullptr);
  }
  level_ms_[l] += ms_since(t0);
  vcycle(l + 1, nullptr, CycleStart::kZero);
  t0 = Clock::now();
  // The prolongation runs inside the post-smoothing's wave, a row just before the first stage
  // reads it. Post-smoothing visits the colours in reverse order: the cycle is then a symmetric
  // operator and can precondition conjugate gradients. With `measure`, the wave also restricts
  // the residual it leaves (unless `last`), which a next cycle starting with
  // CycleStart::kRestricted takes.
  // With `before` (and e as the cycle found it), e and `before` trade storage and the
  // prolongation writes e = before + P e_c: the same values as adding to e, and `before` keeps
  // e's old ones without a copy (at 1024^2, a pass over 12 MB less per measured cycle).
  const bool keep = before && start == CycleStart::kRestricted;
  if (keep) std::swap(F.e, *before);
  const RowHook prolongate = [&](int y) {
    if (keep)
      prolongate_row<Prolong::kFrom>(l, y, before);
    else
      prolongate_row<Prolong::kAdd>(l, y);
  };
  RestrictWhenReady ready(F.h, measure && !last ? C.h : 0);
  const RowHook measure_rows = measure ? restricting(l, ready, measure) : RowHook();
  smooth(l, coarse ? options_.coarse_smooth : options_.post_smooth, true,
         measure ? &measure_rows : nullptr, &prolongate);
  level_ms_[l] += ms_since(t0);
}

// Per-channel dot products on the finest level, summed row by row in a fixed order.
template <int NC>
std::array<double, NC> Multigrid<NC>::dot(const Plane& a, const Plane& b) const {
  const Level& L = levels_[0];
  const size_t n = L.padded();
  std::vector<double> rows(size_t(L.h) * NC, 0.0);
  for_rows(L.h, L.w * NC, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int c = 0; c < NC; ++c) {
        float sum = 0;  // a row in float (vectorised), rows summed in double
        for (const Level::Run& run : L.runs()) {
          const size_t start = c * n + L.at(0, y) + run.offset;
          const float* __restrict pa = &a[start];
          const float* __restrict pb = &b[start];
#pragma omp simd reduction(+ : sum)
          for (int i = 0; i < run.count; ++i) sum += pa[i] * pb[i];
        }
        rows[size_t(y) * NC + c] = sum;
      }
  });
  std::array<double, NC> out{};
  for (int y = 0; y < L.h; ++y)
    for (int c = 0; c < NC; ++c) out[c] += rows[size_t(y) * NC + c];
  return out;
}

// Conjugate gradients on A e = r0, preconditioned by one symmetric V-cycle, each channel on its
// own. Geometric coarsening cannot represent every slow mode of a drawing (a pocket that barriers
// nearly seal off, say); CG removes those few outliers in a handful of iterations, so the solver
// keeps its rate where plain V-cycles would stall. Starts from the FMG answer in levels_[0].e.
template <int NC>
double Multigrid<NC>::conjugate_gradient(double rel, double tolerance, SolveStats& st) {
  Level& L = levels_[0];
  const size_t n = L.padded();
  const Plane r0 = L.rhs;  // the cycles below take the finest right-hand side
  Plane x = L.e, r(r0.size(), 0.0f), p(r0.size(), 0.0f), q(r0.size(), 0.0f);
  residual_of(0, &r0, x, &r);
  std::array<double, NC> rz_old{};
  double last_true = rel;
  // With SolverOptions::max_error. CG's steps are not a fixed-point iteration: one step may
  // change little while the error stays (on drape its largest error fell by only 0.8 per step
  // while single steps changed the answer by a third of it). So the change is the largest of the
  // last four steps, and the rate the geometric mean of their residual ratios, at least 0.5.
  const bool by_error = options_.max_error > 0;
  double estimate = std::numeric_limits<double>::infinity();
  std::vector<double> ratios, changes;
  const auto done = [&] { return by_error ? estimate <= options_.max_error : rel <= tolerance; };
  while (!done() && st.cycles < options_.max_cycles) {
    L.rhs = r;
    vcycle(0, nullptr, CycleStart::kZero);  // z = M r, in L.e
    const std::array<double, NC> rz = dot(r, L.e);
    for (int c = 0; c < NC; ++c) {
      const float beta = rz_old[c] == 0 ? 0.0f : float(rz[c] / rz_old[c]);
      float* pc = &p[c * n];
      const float* z = &L.e[c * n];
      for (size_t i = 0; i < n; ++i) pc[i] = z[i] + beta * pc[i];
    }
    rz_old = rz;
    residual_of(0, nullptr, p, &q);  // q = -A p
    const std::array<double, NC> pq = dot(p, q);
    float change = 0;
    for (int c = 0; c < NC; ++c) {
      const float alpha = pq[c] < 0 ? float(-rz[c] / pq[c]) : 0.0f;
      float *xc = &x[c * n], *rc = &r[c * n];
      const float *pc = &p[c * n], *qc = &q[c * n];
      float largest = 0;
      for (size_t i = 0; i < n; ++i) {
        xc[i] += alpha * pc[i];
        rc[i] += alpha * qc[i];
        largest = std::max(largest, std::abs(pc[i]));
      }
      change = std::max(change, std::abs(alpha) * largest);
    }
    std::array<double, NC> norms = dot(r, r);
    for (double& v : norms) v = std::sqrt(v);
    ++st.cycles;
    const double prev = rel;
    rel = relative(norms);
    st.residual_history.push_back(rel);
    if (by_error) {
      ratios.push_back(rel / prev);
      changes.push_back(change);
      if (ratios.size() >= 4) {
        double log_sum = 0, largest = 0;
        for (size_t i = ratios.size() - 4; i < ratios.size(); ++i) {
          log_sum += std::log(ratios[i]);
          largest = std::max(largest, changes[i]);
        }
        estimate = error_estimate(largest, std::max(0.5, std::exp(log_sum / 4)));
      }
      st.error_estimates.push_back(estimate);
    }
    observe(&r, st);
    // The recursive residual drifts from the true one in float32: when it claims convergence
    // (or has not improved for a while), confirm with the true residual and carry on from it,
    // restarting the directions, unless float32 precision is exhausted.
    if (done() || st.cycles % 16 == 0) {
      residual_of(0, &r0, x, &r);
      std::array<double, NC> true_norms = dot(r, r);
      for (double& v : true_norms) v = std::sqrt(v);
      rel = relative(true_norms);
      st.residual_history.back() = rel;
      if (!done() && rel > 0.5 * last_true && rel < 1e-4) break;  // float32 floor
      last_true = rel;
      std::fill(rz_old.begin(), rz_old.end(), 0.0);
    }
  }
  L.e = x;
  if (by_error) st.converged = done();
  return rel;
}

template <int NC>
void Multigrid<NC>::observe(const Plane* residual_padded, const SolveStats& st) const {
  if (!options_.observer) return;
  const Level& F = levels_[0];
  Plane own;
  if (!residual_padded) {
    own.assign(F.padded() * NC, 0.0f);
    residual_of(0, &F.rhs, F.e, &own);
  }
  const Plane& padded = residual_padded ? *residual_padded : own;
  const size_t n = size_t(F.w) * F.h, nf = F.padded();
  std::vector<float> planes(n * NC);
  for (int c = 0; c < NC; ++c)
    for (int y = 0; y < F.h; ++y)
      for (int x = 0; x < F.w; ++x)
        planes[c * n + size_t(y) * F.w + x] = padded[c * nf + F.vat(x, y)];
  options_.observer(int(st.residual_history.size()) - 1, planes);
}

template <int NC>
double Multigrid<NC>::relative(const std::array<double, NC>& norms) const {
  // A channel whose right-hand side vanishes (say, no blue anywhere) is measured against the
  // largest channel instead, so that a warm start cannot keep it from ever converging.
  const double largest = *std::max_element(b_norm_.begin(), b_norm_.end());
  double worst = 0;
  for (int c = 0; c < NC; ++c) {
    const double scale = b_norm_[c] > 0 ? b_norm_[c] : (largest > 0 ? largest : 1.0);
    worst = std::max(worst, norms[c] / scale);
  }
  return worst;
}

template <int NC>
void Multigrid<NC>::setup() {
  const Problem& p = problem_;
  // Levels: halve until the coarsest has at most 64 points (it is solved exactly).
  int w = p.width, h = p.height, count = 1;
  while (size_t(w) * size_t(h) > 64 && (options_.max_levels <= 0 || count < options_.max_levels)) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    ++count;
  }
  // The workspace's operators are those of the last problem it was set up for: for the same size,
  // only what can have changed is rebuilt (build_coarse), which is the same to the bit.
  const bool reuse = ws_.width == p.width && ws_.height == p.height && int(levels_.size()) == count;
  ws_.width = ws_.height = 0;  // until this setup is complete
  // previous_ trades storage with the finest e (vcycle's `before`): in a new layout its ghost
  // points are zeroed with it (solve_correction assigns it anew).
  if (!reuse) previous_.clear();
  levels_.resize(count);
  prolong_.resize(count - 1);
  std::vector<std::uint8_t> changed = build_finest(fixed_, !reuse);
  // Where most of the operator changed (a renderer's window moved over the image), rebuilding
  // every coarse point is cheaper than finding which to rebuild, and gives the same bits.
  const auto changed_points =
      std::count_if(changed.begin(), changed.end(), [](std::uint8_t c) { return c != 0; });
  const bool incremental = reuse && 4 * size_t(changed_points) < changed.size();
  // Nothing changed (the same problem solved again): every coarse operator and prolongation is
  // the one kept, which an incremental rebuild would leave as it is.
  if (!(reuse && changed_points == 0))
    for (int l = 0; l + 1 < count; ++l) changed = build_coarse(l, incremental ? &changed : nullptr);
  build_coarsest();
  // The cycles' arrays: every interior value is written before it is read, and the ghost points
  // stay 0, so arrays of the same layout are kept as they are.
  for (Level& L : levels_)
    for (auto* v : {&L.e, &L.rhs})
      if (!reuse || v->size() != L.padded() * NC) assign_touched(*v, L.padded() * NC, 0.0f);
  ws_.width = p.width;
  ws_.height = p.height;
  level_ms_.assign(levels_.size(), 0.0);
}

// r = b - A u on the free pixels of the finest level, in double precision, where b = -g plus the
// fixed neighbours' values plus the anchor w_p a_p, and u holds every pixel (fixed ones at their
// values). r_padded receives r in the levels' float layout. Returns the per-channel norms of r
// and, in b_norms, those of b. `u` null: no initial guess, u is the given values on fixed pixels
// and 0 on free ones, read from the problem (the answer is then written once, at the end).
// `row_done(y)` once row y of r_padded is written.
template <int NC>
template <class T>
std::array<double, NC> Multigrid<NC>::residual_double(const T* u, Plane& r_padded,
                                                      std::array<double, NC>* b_norms,
                                                      const RowHook* row_done) const {
  const Problem& p = problem_;
  const Level& F = levels_[0];
  const size_t np = p.pixel_count(), nf = F.padded();
  // Ghost points 0 (a Plane grows unwritten); every interior point is written below.
  if (r_padded.size() != nf * NC) assign_touched(r_padded, nf * NC, 0.0f);
  std::vector<double> rows(size_t(p.height) * NC * 2, 0.0);
#if defined(__AVX512BW__) && defined(__AVX512VL__)
  // Eight pixels at a time: every test of the loop below a mask, each term added only where the
  // loop adds it, in its order (the same residual bits). The sums of squares are kept per lane
  // and added over the lanes at the row's end, in a fixed order: a sum in pixel order was a chain
  // of dependent additions, most of this function's time.
  const auto load = [](const T* q, __mmask8 m) {
    if constexpr (std::is_same_v<T, float>)
      return _mm512_cvtps_pd(_mm256_maskz_loadu_ps(m, q));
    else
      return _mm512_maskz_loadu_pd(m, q);
  };
  const auto widen = [](const float* q, __mmask8 m) {
    return _mm512_cvtps_pd(_mm256_maskz_loadu_ps(m, q));
  };
  // A row's tests are made 64 pixels at a time (one byte load and test each), and each group of
  // eight takes its bits: tests of eight were most of this function's time.
  const auto bits = [](const std::uint8_t* q, __mmask64 m, std::uint8_t b) {
    return std::uint64_t(
        _mm512_test_epi8_mask(_mm512_maskz_loadu_epi8(m, q), _mm512_set1_epi8(char(b))));
  };
  const int W = p.width;
  // Plain pointers: the intrinsics' stores may alias anything, and with the vectors' own
  // pointers read through references GCC loaded them again after every store.
  const T* const u0 = u;
  const float *const value = p.value.data(), *const rhs = p.rhs.empty() ? nullptr : p.rhs.data();
  const float* const anchor = p.anchor_weight.data();
  const std::uint8_t *const fixed = fixed_.data(), *const links = p.links.data();
  float* const r0 = r_padded.data();
  const std::ptrdiff_t nb[4] = {1, -1, W, -W};
  for_rows(p.height, p.width * NC, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      __m512d r2[NC], b2[NC];  // per lane; 0 where a pixel is not free (r and b are 0 there)
      for (int c = 0; c < NC; ++c) r2[c] = b2[c] = _mm512_setzero_pd();
      const size_t row = p.index(0, y), even0 = F.vat(0, y), odd0 = F.vat(1, y);
      for (int x64 = 0; x64 < W; x64 += 64) {
        const std::uint64_t in64 =
            W - x64 >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << (W - x64)) - 1;
        const size_t i64 = row + x64;
        const std::uint64_t free64 = in64 & ~bits(&fixed[i64], in64, 1);
        // East, west, south, north: the link is open (from a free pixel), the neighbour fixed.
        const std::uint64_t open64[4] = {
            free64 & bits(&links[i64], in64, kOpenEast),
            free64 & bits(&links[i64] - 1, x64 == 0 ? in64 & ~std::uint64_t(1) : in64, kOpenEast),
            free64 & bits(&links[i64], in64, kOpenSouth),
            y > 0 ? free64 & bits(&links[i64] - W, in64, kOpenSouth) : 0};
        std::uint64_t fixed64[4], to_fixed64 = 0;
        for (int q = 0; q < 4; ++q) {
          fixed64[q] = bits(&fixed[i64] + nb[q], open64[q], 1);
          to_fixed64 |= open64[q] & fixed64[q];
        }
        for (int x = x64; x < std::min(W, x64 + 64); x += 8) {
          const int shift = x - x64;
          const auto group = [shift](std::uint64_t m) { return __mmask8(m >> shift); };
          const __mmask8 in = group(in64), free = group(free64);
          const __mmask8 open[4] = {group(open64[0]), group(open64[1]), group(open64[2]),
                                    group(open64[3])};
          const __mmask8 fixed_nb[4] = {group(fixed64[0]), group(fixed64[1]), group(fixed64[2]),
                                        group(fixed64[3])};
          const size_t i = row + x, k = even0 + x / 2, k_odd = odd0 + x / 2;  // (x is even)
          const __m512d w = widen(&anchor[i], in);
          const __mmask8 anchored =
              _mm512_mask_cmp_pd_mask(free, w, _mm512_setzero_pd(), _CMP_GT_OQ);
          // Most blocks, with no initial guess: no anchor, and every open link to a free pixel,
          // where u is 0. Then A u is 0 (+0, as the loop below computes it) and r = b, with no
          // value of u read.
          const bool plain = !u0 && !anchored && !group(to_fixed64);
          // (Unrolled, so that the sums r2 and b2 stay in registers.)
#pragma GCC unroll 4
          for (int c = 0; c < NC; ++c) {
            __m512d b = _mm512_setzero_pd(), au = _mm512_setzero_pd();
            if (rhs) b = _mm512_xor_pd(widen(&rhs[c * np + i], free), _mm512_set1_pd(-0.0));
            if (!plain) {
              // Without a guess u is +0 on free pixels and the value on fixed ones (a free
              // pixel's open links reach no unreachable one: it would be unreachable too).
              const T* uc = u0 ? &u0[c * np + i] : nullptr;
              const float* vc = &value[c * np + i];
              if (uc) prefetch(uc, 2 * W);
              prefetch(vc, W);  // rows read next
              const __m512d ui = uc ? load(uc, free) : _mm512_setzero_pd();
              if (anchored) {
                au = _mm512_mask3_fmadd_pd(ui, w, au, anchored);
                b = _mm512_mask3_fmadd_pd(w, widen(vc, anchored), b, anchored);
              }
              // Without a guess, a link to a free pixel adds u = +0 and subtracts it, which leaves
              // au at +0: the links matter only where one reaches a fixed pixel (an anchored
              // block, along a curve, mostly has none; 0.5 ms of a new 1024^2 drawing's setup).
              if (uc || group(to_fixed64))
                for (int q = 0; q < 4; ++q) {  // (no branch on open[q]: with no lane, no change)
                  const __m512d un = uc ? load(uc + nb[q], open[q])
                                        : widen(vc + nb[q], __mmask8(open[q] & fixed_nb[q]));
                  au = _mm512_mask_add_pd(au, open[q], au, ui);
                  b = _mm512_mask_add_pd(b, __mmask8(open[q] & fixed_nb[q]), b, un);
                  au = _mm512_mask_sub_pd(au, __mmask8(open[q] & ~fixed_nb[q]), au, un);
                }
            }
            const __m512d r = _mm512_maskz_sub_pd(free, b, au);
            // x is even: the even lanes go to the row's even half, the odd ones to its odd half
            // (compressed in registers: a compressing store is microcoded, and slow, on Zen 4).
            const __m256 r32 = _mm512_cvtpd_ps(r);
            const __mmask8 even = __mmask8(in & 0x55), odd = __mmask8(in & 0xAA);
            _mm256_mask_storeu_ps(&r0[c * nf + k], __mmask8((1u << _mm_popcnt_u32(even)) - 1),
                                  _mm256_maskz_compress_ps(even, r32));
            _mm256_mask_storeu_ps(&r0[c * nf + k_odd], __mmask8((1u << _mm_popcnt_u32(odd)) - 1),
                                  _mm256_maskz_compress_ps(odd, r32));
            r2[c] = _mm512_fmadd_pd(r, r, r2[c]);
            b2[c] = _mm512_fmadd_pd(b, b, b2[c]);
          }
        }
      }
      double* sums = &rows[size_t(y) * NC * 2];
      for (int c = 0; c < NC; ++c) {
        alignas(64) double rs[8], bs[8];
        _mm512_store_pd(rs, r2[c]);
        _mm512_store_pd(bs, b2[c]);
        for (int j = 0; j < 8; ++j) {
          sums[c * 2] += rs[j];
          sums[c * 2 + 1] += bs[j];
        }
      }
      if (row_done) (*row_done)(y);
    }
  });
#else
  for_rows(p.height, p.width * NC, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < p.width; ++x) {
        const size_t i = p.index(x, y), k = F.vat(x, y);
        if (fixed_[i]) {
          for (int c = 0; c < NC; ++c) r_padded[c * nf + k] = 0.0f;
          continue;
        }
        const bool open[4] = {
            (p.links[i] & kOpenEast) != 0, x > 0 && (p.links[i - 1] & kOpenEast) != 0,
            (p.links[i] & kOpenSouth) != 0, y > 0 && (p.links[i - p.width] & kOpenSouth) != 0};
        const size_t nb[4] = {i + 1, i - 1, i + p.width, i - p.width};
        const double w = p.anchor_weight[i];
        for (int c = 0; c < NC; ++c) {
          // Without a guess: the given value on a fixed pixel, 0 on a free one.
          const auto uc = [&, o = c * np](size_t j) {
            return u ? double(u[o + j]) : p.fixed[j] ? double(p.value[o + j]) : 0.0;
          };
          double b = p.rhs.empty() ? 0.0 : -double(p.rhs[c * np + i]);
          double au = 0;
          if (w > 0) {
            au += w * uc(i);
            b += w * p.value[c * np + i];
          }
          for (int q = 0; q < 4; ++q)
            if (open[q]) {
              au += uc(i);
              if (fixed_[nb[q]])
                b += uc(nb[q]);
              else
                au -= uc(nb[q]);
            }
          const double r = b - au;
          r_padded[c * nf + k] = float(r);
          rows[(size_t(y) * NC + c) * 2] += r * r;
          rows[(size_t(y) * NC + c) * 2 + 1] += b * b;
        }
      }
      if (row_done) (*row_done)(y);
    }
  });
#endif
  std::array<double, NC> norms{};
  for (int y = 0; y < p.height; ++y)
    for (int c = 0; c < NC; ++c) {
      norms[c] += rows[(size_t(y) * NC + c) * 2];
      if (b_norms) (*b_norms)[c] += rows[(size_t(y) * NC + c) * 2 + 1];
    }
  for (double& v : norms) v = std::sqrt(v);
  if (b_norms)
    for (double& v : *b_norms) v = std::sqrt(v);
  return norms;
}

template <int NC>
float Multigrid<NC>::change_of_row(int y) const {
  const Level& L = levels_[0];
  const size_t n = L.padded();
  float m = 0;
  for (int c = 0; c < NC; ++c)
    for (const Level::Run& run : L.runs()) {
      const size_t start = c * n + L.at(0, y) + run.offset;
      const float* __restrict e = &L.e[start];
      if (previous_zero_) {  // e - 0 is e, to the bit
#pragma omp simd reduction(max : m)
        for (int i = 0; i < run.count; ++i) m = std::max(m, std::abs(e[i]));
        continue;
      }
      const float* __restrict b = &previous_[start];
#pragma omp simd reduction(max : m)
      for (int i = 0; i < run.count; ++i) m = std::max(m, std::abs(e[i] - b[i]));
    }
  return m;
}

// Solves A e = r0 (float32) into levels_[0].e: FMG, then CG-accelerated or plain V-cycles until
// the stopping rule holds (the residual relative to b_norm_ below `tolerance`, or with
// SolverOptions::max_error the estimated error below it) or float32 precision is exhausted.
// `rel` is the relative residual of r0 (the finest right-hand side). With full multigrid,
// levels_[1].rhs already holds r0 restricted (run() restricts it as it computes r0).
template <int NC>
double Multigrid<NC>::solve_correction(double rel, double tolerance, SolveStats& st) {
  const int count = int(levels_.size());
  const bool by_error = options_.max_error > 0;
  Level& F = levels_[0];
  // After a finest cycle: the residual's norms and the change since the last cycle, measured
  // row by row in the post-smoothing's wave while the rows are in cache (the sums of
  // residual_norms, and the change from previous_, without two more passes over the finest level).
  std::vector<double> row_norms(size_t(F.h) * NC, 0.0);
  std::vector<float> row_change(size_t(F.h), 0.0f);
  const auto keep_norms = [&](int y, const float* norms) {
    for (int c = 0; c < NC; ++c) row_norms[size_t(y) * NC + c] = norms[c];
  };
  const MeasureHook measure = [&](int y, const float* norms) {
    keep_norms(y, norms);
    if (by_error) row_change[size_t(y)] = change_of_row(y);
  };
  // Full multigrid's finest cycle: its norms only (the rule takes no change from it: below).
  const MeasureHook measure_norms = keep_norms;
  const auto measured_change = [&] {
    return row_change.empty() ? 0.0
                              : double(*std::max_element(row_change.begin(), row_change.end()));
  };
  double estimate = rel == 0 ? 0.0 : std::numeric_limits<double>::infinity();
  const auto done = [&] { return by_error ? estimate <= options_.max_error : rel <= tolerance; };
  // The correction before the first cycle is 0 (F.e above): previous_ is not filled with zeros
  // but marked as such (previous_zero_) until a cycle keeps the correction it started from there
  // (vcycle's `before`). Its ghost points are 0, as e's: the two trade storage.
  if (by_error) {
    if (previous_.size() != F.e.size()) assign_touched(previous_, F.e.size(), 0.0f);
    previous_zero_ = true;
  }
  // The correction starts at 0, or with FMG as the coarser levels' answer (written by the
  // finest V-cycle's first pass).
  const bool full_multigrid = !done() && options_.full_multigrid;
  if (!full_multigrid) fill_zero(F.e);
  if (full_multigrid) {
    // FMG: restrict r0 to every level, solve the coarsest exactly, then interpolate each
    // level's answer as the next finer one's start and run one V-cycle there.
    // (Level 1's was restricted by run() as it computed r0, row by row.)
    for (int l = 1; l + 1 < count; ++l)
      for_rows(levels_[l + 1].h, levels_[l + 1].w * 2, [&](int J0, int J1) {
        for (int J = J0; J < J1; ++J) restrict_rhs_row(l, J);
      });
    fill_zero(levels_.back().e);
    solve_coarsest();
    for (int l = count - 2; l >= 0; --l) {
      vcycle(l, l == 0 ? &measure_norms : nullptr, CycleStart::kFromCoarse);
      if (l == 0) previous_zero_ = false;
    }
    const bool measured = count > 1;  // (one level: no finest cycle ran)
    rel = relative(measured ? sum_row_norms(row_norms, F.h) : residual_norms(0));
    st.residual_history.push_back(rel);
    // No estimate yet: the FMG's change is mostly the coarse answer's interpolation error,
    // which the finest cycle removes far faster than the error that remains (measured: the
    // estimate would be 10-100x too small).
    if (by_error) {
      previous_zero_ = false;
      st.error_estimates.push_back(estimate);
    }
    observe(nullptr, st);
  }
  double last_change = 0;            // of the previous V-cycle, 0 before the first
  double last_rate = 0;              // its rate, as the rule takes it (or its residual's)
  bool restricted = full_multigrid;  // level 1 holds the residual of a measured finest cycle
  bool unrestricted = false;         // the last cycle, expected to be the last, did not restrict
  while (!done() && st.cycles < options_.max_cycles) {
    if (unrestricted) restrict_residual(0);  // (expected wrongly: 6 of 34 such cycles, below)
    // A cycle that the rule will likely stop after does not restrict the residual it leaves (0.6
    // ms at 1024^2): expected when the rule's estimate, with this cycle changing the answer by
    // the last one's change times its rate, falls within the bound. Over the 27 solves of
    // docs/performance.md, of 34 cycles with an estimate: 21 expected and last, 6 expected and
    // not (a third cycle, whose estimate after two was 0.29-0.35/255: a pass of their own
    // restricts them), 1 not expected and last.
    const bool last = st.cycles + 1 >= options_.max_cycles ||
                      (by_error && last_change > 0 &&
                       error_estimate(last_change * last_rate, last_rate) <= options_.max_error);
    // No pre-smoothing on the finest level: the last cycle's post-smoothing left it smoothed, and
    // restricted its residual (measured for the stopping rule) to level 1, or a pass of its own
    // did (restrict_residual, above). Sweeps before the
    // coarse correction as well cost a wave over the finest level (5-6 ms of a 1024^2 solve's
    // two cycles) for a little more per cycle: 165 cycles against 173 over 27 solves of nine
    // drawings at 256^2 to 1024^2, all within the 8-bit bound (docs/performance.md).
    vcycle(0, &measure, restricted ? CycleStart::kRestricted : CycleStart::kHeld,
           by_error && !previous_zero_ ? &previous_ : nullptr, last);
    restricted = true;
    unrestricted = last && count > 1;  // (one level: no coarser one to restrict to)
    previous_zero_ = false;
    ++st.cycles;
    const double prev = rel;
    rel = relative(sum_row_norms(row_norms, F.h));
    st.residual_history.push_back(rel);
    if (by_error) {
      // The rate: the residual's, or the change's from one cycle to the next when larger (the
      // residual falls up to twice as fast as the largest error). No estimate after the first
      // cycle: with a single ratio it came out 5-50x too small where a few modes converge
      // slowly (drawings with nearly sealed pockets, a warm start that is off in one).
      const double change = measured_change();
      last_rate = last_change > 0 ? std::max(rel / prev, change / last_change) : rel / prev;
      if (last_change > 0) estimate = error_estimate(change, last_rate);
      last_change = change;
      st.error_estimates.push_back(estimate);
    }
    observe(nullptr, st);
    // A cycle that gains less than 2x meets a mode the coarse grids cannot represent: from
    // here conjugate gradients, with the symmetric cycle (pre- and post-smoothed) as
    // preconditioner, take over. Not sooner: CG's
    // stopping rule needs four steps before its first estimate, so cycles that still gain 2-3x
    // stop earlier by themselves (frame 1 of the default scene at 1024^2: 0.36 per cycle, 5
    // cycles instead of 4 cycles and 5 CG steps).
    if (options_.krylov && rel > 0.5 * prev && !done())
      return conjugate_gradient(rel, tolerance, st);
    if (rel > 0.9 * prev && rel < 1e-4) break;  // float32 floor
  }
  if (by_error) st.converged = done();
  return rel;
}

template <int NC>
Solution Multigrid<NC>::run(const std::vector<float>* guess, std::vector<float>* buffer) {
  const Problem& p = problem_;
  const auto t_setup = Clock::now();
  Solution out;
  out.width = p.width;
  out.height = p.height;
  out.channels = NC;
  SolveStats& st = out.stats;
  st.floating_pixels = mark_fixed(fixed_);
  setup();
  st.levels = int(levels_.size());

  // u: fixed values on fixed pixels, the guess (or 0) on free ones; unreachable pixels are 0.
  // In double precision only when the tolerance is below what float32 reaches (refinement).
  const bool by_error = options_.max_error > 0;
  const bool refine = !by_error && options_.tolerance < 2e-6;
  const size_t np = p.pixel_count();
  const auto initial = [&](auto& u) {
    reserve_touched(u, np * NC);
    u.resize(np * NC);
    // Plain pointers and every load made before the selects, so that the loop vectorises; the
    // guess may be u itself, read at each place before it is written there (ivdep).
    auto* const start = u.data();
    const std::uint8_t *given = p.fixed.data(), *fixed = fixed_.data();
    const float *value = p.value.data(), *kept = guess ? guess->data() : nullptr;
    for_rows(p.height, p.width * NC, [&](int y0, int y1) {
      const size_t i0 = p.index(0, y0), i1 = p.index(0, y1);
      for (int c = 0; c < NC; ++c) {
        const size_t o = c * np;
        if (kept) {
#pragma GCC ivdep
          for (size_t i = i0; i < i1; ++i) {
            const float v = value[o + i], g = kept[o + i];
            start[o + i] = given[i] ? v : (fixed[i] ? 0.0f : g);
          }
        } else {
          // The value loaded everywhere and then selected: a load only where given[i] holds
          // kept this loop scalar, a branch a pixel (GCC 12).
#pragma GCC ivdep
          for (size_t i = i0; i < i1; ++i) {
            const float v = value[o + i];
            start[o + i] = given[i] ? v : 0.0f;
          }
        }
      }
    });
  };
  // u += the correction solved on the finest level, whose rows hold their even points, then
  // their odd ones (Level::odd): each pair of pixels takes one of each, so that the loop
  // vectorises (a loop per run, with its stride a variable, did not). `unwritten`: a solve
  // without a guess, whose u is written here for the first time, as initial() would have
  // written it plus the correction (one pass over the answer rather than two).
  const auto add_correction = [&](auto& u, bool unwritten) {
    if (unwritten) {
      reserve_touched(u, np * NC);
      u.resize(np * NC);
    }
    const Level& F = levels_[0];
    const size_t nf = F.padded();
    const int pairs = F.odd_count();
    for_rows(p.height, p.width * NC, [&](int y0, int y1) {
      for (int c = 0; c < NC; ++c)
        for (int y = y0; y < y1; ++y) {
          const size_t at = c * np + p.index(0, y);
          auto* __restrict to = &u[at];
          const float* __restrict even = &F.e[c * nf + F.vat(0, y)];
          const float* __restrict odd = &F.e[c * nf + F.vat(1, y)];
          const std::uint8_t* __restrict given = &p.fixed[p.index(0, y)];
          const float* __restrict value = &p.value[at];
          // u at pixel x before the correction: what it holds, or (unwritten) initial()'s value
          const auto add = [&](const auto& before) {
            for (int i = 0; i < pairs; ++i) {
              to[2 * i] = before(2 * i) + even[i];
              to[2 * i + 1] = before(2 * i + 1) + odd[i];
            }
            if (F.w & 1) to[F.w - 1] = before(F.w - 1) + even[pairs];
          };
          if (unwritten)
            add([&](int x) {
              const float v = value[x];  // loaded before the select: a conditional load is scalar
              return given[x] ? v : 0.0f;
            });
          else
            add([&](int x) { return to[x]; });
        }
    });
  };
  std::vector<float> u32;
  // The caller's buffer, with the guess in it when it is the guess: initial() reads each guess
  // value before it writes the same place.
  if (buffer) {
    const bool is_guess = guess == buffer;
    u32.swap(*buffer);
    if (is_guess) guess = &u32;
  }
  std::vector<double> u64;
  // The residual of the initial guess is the finest level's right-hand side.
  Plane& r = levels_[0].rhs;
  // The scale of relative residuals is the right-hand side b of the free pixels' system.
  b_norm_.fill(0.0);
  // Full multigrid starts by restricting r to every level: level 1's rows are restricted as the
  // residual's rows are written, while they are in cache (a pass over the finest level less).
  // (solve_correction's full multigrid counts on it.)
  const auto residual = [&](const auto* u, std::array<double, NC>* b_norms) {
    if (!options_.full_multigrid || levels_.size() == 1)
      return relative(residual_double(u, r, b_norms));
    RestrictWhenReady ready(levels_[0].h, levels_[1].h);
    const RowHook restrict_rows = [&](int y) {
      ready.row_done(y, [&](int J) { restrict_rhs_row(0, J); });
    };
    return relative(residual_double(u, r, b_norms, &restrict_rows));
  };
  // Without a guess (and in float32), u is written with the correction, once (add_correction).
  const bool cold = !refine && !guess;
  double rel;
  if (refine) {
    initial(u64);
    rel = residual(u64.data(), &b_norm_);
  } else if (cold) {
    rel = residual(static_cast<const float*>(nullptr), &b_norm_);
  } else {
    initial(u32);
    rel = residual(u32.data(), &b_norm_);
  }
  st.initial_residual = rel;
  st.setup_ms = ms_since(t_setup);

  const auto t_solve = Clock::now();
  if (!refine) {
    st.converged = rel == 0;
    if (by_error ? rel > 0 : rel > options_.tolerance) {
      rel = solve_correction(rel, options_.tolerance, st);
      add_correction(u32, cold);
    } else if (cold) {
      initial(u32);
    }
  } else {
    // Mixed precision: the float32 solve reaches a relative residual of about 1e-6. For a
    // tighter tolerance the residual of the double-precision answer is solved for again
    // (iterative refinement); each round gains about five digits.
    for (int round = 0; round < 3 && rel > options_.tolerance; ++round) {
      solve_correction(rel, options_.tolerance, st);
      add_correction(u64, false);
      const double prev = rel;
      rel = residual(u64.data(), nullptr);
      if (rel > 0.5 * prev) break;
    }
    u32.assign(u64.begin(), u64.end());
  }
  st.final_residual = rel;
  if (!by_error) st.converged = rel <= options_.tolerance;
  out.planes = std::move(u32);
  st.solve_ms = ms_since(t_solve);
  st.level_ms = level_ms_;
  return out;
}

template <int NC>
std::vector<double> Multigrid<NC>::factors(int cycles, unsigned seed) {
  mark_fixed(fixed_);
  setup();
  Level& F = levels_[0];
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int y = 0; y < F.h; ++y)
    for (int x = 0; x < F.w; ++x)
      for (int c = 0; c < NC; ++c)
        if (F.alive[F.at(x, y)]) F.e[c * F.padded() + F.vat(x, y)] = unit(rng);
  b_norm_.fill(1.0);
  std::fill(F.rhs.begin(), F.rhs.end(), 0.0f);
  std::vector<double> out;
  double before = relative(residual_norms(0));
  for (int k = 0; k < cycles && before > 0; ++k) {
    vcycle(0);
    const double after = relative(residual_norms(0));
    out.push_back(after / before);
    // Rescale the error to unit residual so that float32 round-off never dominates.
    for (float& v : F.e) v = float(v / after);
    before = relative(residual_norms(0));
  }
  return out;
}

}  // namespace

std::vector<double> measure_vcycle_factors(const Problem& problem, int cycles,
                                           const SolverOptions& options, unsigned seed) {
  check_problem(problem);
  Problem p = problem;
  p.channels = 1;
  p.value.assign(p.pixel_count(), 0.0f);
  p.rhs.clear();
  Workspace ws;
  return Multigrid<1>(p, options, ws).factors(cycles, seed);
}

namespace {

// Runs a solve in a kept workspace: an idle one, or a new one when every kept one is in use.
// Workspaces are kept per channel count and returned after the solve, so the memory kept is that
// of the most solves ever in flight at once, not one per thread: `wisp render` shades one frame
// at a time, on whichever thread, and its consecutive frames meet one workspace (whose next solve
// of the same size rebuilds only what changed).
struct WorkspacePool {
  std::mutex mutex;
  std::vector<std::unique_ptr<Workspace>> idle;
};
template <int NC>
WorkspacePool& workspace_pool() {
  static WorkspacePool pool;
  return pool;
}

template <int NC>
Solution solve_in_workspace(const Problem& problem, const SolverOptions& options,
                            const std::vector<float>* initial_guess,
                            std::vector<float>* buffer = nullptr) {
  WorkspacePool& pool = workspace_pool<NC>();
  std::unique_ptr<Workspace> ws;
  {
    const std::lock_guard<std::mutex> lock(pool.mutex);
    if (!pool.idle.empty()) {
      ws = std::move(pool.idle.back());
      pool.idle.pop_back();
    }
  }
  if (!ws) ws = std::make_unique<Workspace>();
  Solution solution = Multigrid<NC>(problem, options, *ws).run(initial_guess, buffer);
  const std::lock_guard<std::mutex> lock(pool.mutex);
  pool.idle.push_back(std::move(ws));  // (not after an exception: that workspace is dropped)
  return solution;
}

template <int NC>
void release_pool() {
  WorkspacePool& pool = workspace_pool<NC>();
  std::vector<std::unique_ptr<Workspace>> idle;
  {
    const std::lock_guard<std::mutex> lock(pool.mutex);
    idle.swap(pool.idle);
  }
}

}  // namespace

void release_solver_workspaces() {
  release_pool<1>();
  release_pool<2>();
  release_pool<3>();
  release_pool<4>();
}

namespace {

Solution solve_with(const Problem& problem, const SolverOptions& options,
                    const std::vector<float>* initial_guess, std::vector<float>* buffer) {
  check_problem(problem);
  if (initial_guess && initial_guess->size() != problem.pixel_count() * problem.channels)
    throw std::invalid_argument("solver: initial guess has the wrong size");
  switch (problem.channels) {
    case 1:
      return solve_in_workspace<1>(problem, options, initial_guess, buffer);
    case 2:
      return solve_in_workspace<2>(problem, options, initial_guess, buffer);
    case 3:
      return solve_in_workspace<3>(problem, options, initial_guess, buffer);
    default:
      return solve_in_workspace<4>(problem, options, initial_guess, buffer);
  }
}

}  // namespace

Solution solve_multigrid(const Problem& problem, const SolverOptions& options,
                         const std::vector<float>* initial_guess) {
  return solve_with(problem, options, initial_guess, nullptr);
}

Solution solve_multigrid(const Problem& problem, const SolverOptions& options,
                         std::vector<float>&& initial_guess) {
  return solve_with(problem, options, &initial_guess, &initial_guess);
}

Solution solve_multigrid_into(const Problem& problem, const SolverOptions& options,
                              std::vector<float>&& storage) {
  return solve_with(problem, options, nullptr, &storage);
}

}  // namespace wisp::diffusion
