// Problem construction helpers (see problem.hpp).
#include "diffusion/problem.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#if defined(__AVX512BW__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "diffusion/fresh_memory.hpp"

namespace wisp::diffusion {

Problem make_open_problem(int width, int height, int channels) {
  Problem p;
  p.width = width;
  p.height = height;
  p.channels = channels;
  const size_t n = p.pixel_count();
  // Fresh arrays of a whole image (18 MB at 1024^2, 3 channels): their pages are faulted in by
  // the worker threads together (fresh_memory.hpp).
  assign_touched(p.fixed, n, std::uint8_t(0));
  // Every link open, but east of the last column and south of the last row.
  assign_touched(p.links, n, std::uint8_t(kOpenEast | kOpenSouth));
  if (n > 0) {
    for (int y = 0; y < height; ++y) p.links[p.index(width - 1, y)] &= std::uint8_t(~kOpenEast);
    for (int x = 0; x < width; ++x) p.links[p.index(x, height - 1)] &= std::uint8_t(~kOpenSouth);
  }
  assign_touched(p.anchor_weight, n, 0.0f);
  assign_touched(p.value, n * channels, 0.0f);
  return p;
}

void add_gradient_field(Problem& p, const std::vector<float>& wx, const std::vector<float>& wy) {
  const size_t n = p.pixel_count();
  if (wx.size() != n * p.channels || wy.size() != n * p.channels)
    throw std::invalid_argument("gradient field: expected " + std::to_string(p.channels) +
                                " planes of " + std::to_string(n) + " values");
  if (p.rhs.empty()) p.rhs.assign(n * p.channels, 0.0f);
  for (int c = 0; c < p.channels; ++c) {
    float* g = p.rhs.data() + c * n;
    const float* gx = wx.data() + c * n;
    const float* gy = wy.data() + c * n;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const size_t i = p.index(x, y);
        if (p.links[i] & kOpenEast) {
          g[i] += gx[i];
          g[i + 1] -= gx[i];
        }
        if (p.links[i] & kOpenSouth) {
          g[i] += gy[i];
          g[i + p.width] -= gy[i];
        }
      }
  }
}

namespace {

// The last pixel of the run that starts at x0 of a row of W pixels: links are open east from x0
// up to it, and not from it (or it is the row's last pixel). Sixty-four links a step where
// AVX-512 is there: the byte loop alone was a quarter of reached_from_fixed's time.
int run_end(const std::uint8_t* links, int x0, int W) {
  int x = x0;
#if defined(__AVX512BW__)
  for (; x + 64 < W; x += 64) {  // links x .. x + 63, none of them the row's last pixel's
    const __mmask64 closed =
        _mm512_testn_epi8_mask(_mm512_loadu_si512(links + x), _mm512_set1_epi8(char(kOpenEast)));
    if (closed) return x + __builtin_ctzll(closed);
  }
#endif
  while (x + 1 < W && (links[x] & kOpenEast)) ++x;
  return x;
}

}  // namespace

// Connected components of the pixels by runs: a run is a piece of a row joined by open east links,
// and two runs of neighbouring rows are merged (union-find) when an open south link joins them
// anywhere along their overlap. A pixel is reached when its component holds a fixed or anchored
// pixel. Rows are walked a run at a time, keeping the row above as a list of runs rather than a
// run number per pixel: what is left per pixel are loops over bytes without exits (the run's end,
// its seeds, the open south links of an overlap), 2.7x faster for a drawing at 1024^2. Runs
// partition the pixels in raster order, so run r covers the pixels start[r] to start[r + 1] - 1.
//
// Bands of rows are walked in parallel, each numbering its own runs; the bands' numbers are then
// put end to end and the runs on either side of each band boundary merged, as the walk of one
// band merges those of its rows. Components do not depend on the order of the merges: the
// result is the same for any number of bands.
std::vector<std::uint8_t> reached_from_fixed(const Problem& p) {
  const int W = p.width, H = p.height;
  struct Run {
    int x0, x1, id;  // pixels x0 .. x1 of the row
  };
  struct Band {
    std::vector<int> parent, start;
    std::vector<std::uint8_t> seeded;
    std::vector<Run> first, last;  // the runs of the band's first and last rows
  };
  const auto find = [](std::vector<int>& parent, int r) {
    while (parent[r] != r) r = parent[r] = parent[parent[r]];
    return r;
  };
  // Merges `run` (pixels x0 .. x1 of a row) with the runs `above` (of the row above, their ids
  // plus `offset`) that an open south link from that row (`up`) joins to it. `a`: the first run
  // above that can overlap this one, kept from run to run along the row.
  const auto join = [&](std::vector<int>& parent, const std::vector<Run>& above, int offset,
                        size_t& a, int x0, int x1, int run, const std::uint8_t* up) {
    while (above[a].x1 < x0) ++a;
    for (size_t b = a; b < above.size() && above[b].x0 <= x1; ++b) {
      unsigned open = 0;
      for (int x = std::max(x0, above[b].x0); x <= std::min(x1, above[b].x1); ++x)
        open |= up[x] & kOpenSouth;
      if (!open) continue;
      const int ra = find(parent, above[b].id + offset), rb = find(parent, run);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  };
  const auto walk = [&](int y0, int y1, Band& band) {
    std::vector<Run> above, here;
    for (int y = y0; y < y1; ++y) {
      const size_t row = p.index(0, y);
      const std::uint8_t *links = &p.links[row], *fixed = &p.fixed[row];
      const float* weight = &p.anchor_weight[row];
      here.clear();
      size_t a = 0;
      for (int x0 = 0; x0 < W;) {
        const int x1 = run_end(links, x0, W);
        const int run = int(band.parent.size());
        band.parent.push_back(run);
        band.start.push_back(int(row) + x0);
        unsigned seed = 0;  // (an unsigned OR over the run, without an exit: it vectorises)
        for (int x = x0; x <= x1; ++x) seed |= unsigned(fixed[x] != 0) | unsigned(weight[x] > 0);
        band.seeded.push_back(std::uint8_t(seed));
        if (y > y0) join(band.parent, above, 0, a, x0, x1, run, links - W);
        here.push_back({x0, x1, run});
        x0 = x1 + 1;
      }
      if (y == y0) band.first = here;
      std::swap(above, here);
    }
    band.last = std::move(above);
  };
  const int bands = std::clamp(H / 128, 1, 8);
  std::vector<Band> band(size_t(bands), Band{});
  const auto first_row = [&](int b) { return int(int64_t(H) * b / bands); };
  tbb::parallel_for(0, bands, [&](int b) { walk(first_row(b), first_row(b + 1), band[b]); });
  // One numbering: band b's runs after those of the bands before it (from offset[b]).
  std::vector<int> parent, start, offset;
  std::vector<std::uint8_t> seeded;
  for (int b = 0; b < bands; ++b) {
    const Band& B = band[b];
    offset.push_back(int(parent.size()));
    for (int r : B.parent) parent.push_back(r + offset[b]);
    start.insert(start.end(), B.start.begin(), B.start.end());
    seeded.insert(seeded.end(), B.seeded.begin(), B.seeded.end());
    if (b == 0) continue;
    // The band's first row against the last row of the band above.
    const std::uint8_t* up = &p.links[p.index(0, first_row(b) - 1)];
    size_t a = 0;
    for (const Run& r : B.first)
      join(parent, band[b - 1].last, offset[b - 1], a, r.x0, r.x1, r.id + offset[b], up);
  }
  const int runs = int(parent.size());
  std::vector<std::uint8_t> component_seeded(runs, 0);
  for (int r = 0; r < runs; ++r) component_seeded[find(parent, r)] |= seeded[r];
  std::vector<std::uint8_t> reached(p.pixel_count());
  start.push_back(int(p.pixel_count()));
  for (int r = 0; r < runs; ++r)
    std::fill(reached.begin() + start[r], reached.begin() + start[r + 1],
              component_seeded[find(parent, r)]);
  return reached;
}

namespace {

// The largest magnitude of `count` floats as bits: below the exponent of all ones where none is
// NaN or infinite (an integer maximum, which vectorises).
std::uint32_t largest_bits(const float* values, size_t count) {
  std::uint32_t largest = 0;
  for (size_t i = 0; i < count; ++i) {
    std::uint32_t bits;
    std::memcpy(&bits, &values[i], sizeof bits);
    largest = std::max(largest, bits & 0x7fffffffu);
  }
  return largest;
}
constexpr std::uint32_t kNotFinite = 0x7f800000u;

// What check_problem judges of a problem's arrays, gathered over pixels [i0, i1).
struct ArrayFlags {
  std::uint32_t value = 0, rhs = 0;  // largest magnitudes as bits (largest_bits)
  unsigned negative = 0, on_fixed = 0;
  ArrayFlags& operator|=(const ArrayFlags& o) {
    value = std::max(value, o.value);
    rhs = std::max(rhs, o.rhs);
    negative |= o.negative;
    on_fixed |= o.on_fixed;
    return *this;
  }
};
ArrayFlags array_flags(const Problem& p, size_t i0, size_t i1) {
  const size_t n = p.pixel_count();
  ArrayFlags f;
  for (int c = 0; c < p.channels; ++c) {
    f.value = std::max(f.value, largest_bits(&p.value[c * n + i0], i1 - i0));
    if (!p.rhs.empty()) f.rhs = std::max(f.rhs, largest_bits(&p.rhs[c * n + i0], i1 - i0));
  }
  unsigned negative = 0, on_fixed = 0;  // (unsigned flags: bools kept the loop scalar)
  const float* weight = p.anchor_weight.data();
  const std::uint8_t* fixed = p.fixed.data();
  for (size_t i = i0; i < i1; ++i) {
    negative |= unsigned(!(weight[i] >= 0.0f)) |
                unsigned(!(weight[i] <= std::numeric_limits<float>::max()));
    on_fixed |= unsigned(weight[i] > 0.0f) & unsigned(fixed[i] != 0);
  }
  f.negative = negative;
  f.on_fixed = on_fixed;
  return f;
}

}  // namespace

void check_problem(const Problem& p) {
  if (p.width <= 0 || p.height <= 0)
    throw std::invalid_argument("problem: image size must be positive, got " +
                                std::to_string(p.width) + "x" + std::to_string(p.height));
  if (p.channels < 1 || p.channels > 4)
    throw std::invalid_argument("problem: channels must be 1 to 4");
  const size_t n = p.pixel_count();
  if (p.fixed.size() != n || p.links.size() != n || p.anchor_weight.size() != n ||
      p.value.size() != n * p.channels || (!p.rhs.empty() && p.rhs.size() != n * p.channels))
    throw std::invalid_argument("problem: array sizes do not match the image size");
  // Each array is scanned whole and judged once: a test that can leave the loop at every value
  // keeps it scalar (2.5 ms a solve at 1024^2), a flag gathered over all of them vectorises.
  // Pieces of the image in parallel (one thread took 0.35 ms at 1024^2, before every solve).
  const ArrayFlags f = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, size_t(1) << 16), ArrayFlags{},
      [&](const tbb::blocked_range<size_t>& r, ArrayFlags acc) {
        return acc |= array_flags(p, r.begin(), r.end());
      },
      [](ArrayFlags a, const ArrayFlags& b) { return a |= b; });
  if (f.value >= kNotFinite)
    throw std::invalid_argument("problem: a fixed or anchor value is not finite");
  if (f.negative)
    throw std::invalid_argument("problem: an anchor weight is negative or not finite");
  if (f.on_fixed) throw std::invalid_argument("problem: a fixed pixel has an anchor");
  if (f.rhs >= kNotFinite) throw std::invalid_argument("problem: a right-hand side is not finite");
  for (int y = 0; y < p.height; ++y) {
    if ((p.links[p.index(p.width - 1, y)] & kOpenEast) != 0)
      throw std::invalid_argument("problem: a link leaves the image on the east border");
  }
  for (int x = 0; x < p.width; ++x)
    if ((p.links[p.index(x, p.height - 1)] & kOpenSouth) != 0)
      throw std::invalid_argument("problem: a link leaves the image on the south border");
}

}  // namespace wisp::diffusion
