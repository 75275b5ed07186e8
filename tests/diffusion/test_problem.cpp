// reached_from_fixed (diffusion/problem.hpp) against a plain flood fill from every fixed and
// anchored pixel over the open links, on random link patterns from nearly sealed to nearly open.
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>
#include <vector>

#include "diffusion/problem.hpp"

using namespace wisp::diffusion;

namespace {

// Pixels joined to a fixed or anchored pixel through open links, by breadth-first search.
std::vector<std::uint8_t> flood_fill(const Problem& p) {
  const int W = p.width, H = p.height;
  std::vector<std::uint8_t> reached(p.pixel_count(), 0);
  std::vector<int> queue;
  for (int i = 0; i < int(p.pixel_count()); ++i)
    if (p.fixed[i] || p.anchor_weight[i] > 0) reached[i] = 1, queue.push_back(i);
  for (size_t q = 0; q < queue.size(); ++q) {
    const int i = queue[q], x = i % W, y = i / W;
    const auto visit = [&](int j, bool open) {
      if (open && !reached[j]) reached[j] = 1, queue.push_back(j);
    };
    if (x + 1 < W) visit(i + 1, p.links[i] & kOpenEast);
    if (x > 0) visit(i - 1, p.links[i - 1] & kOpenEast);
    if (y + 1 < H) visit(i + W, p.links[i] & kOpenSouth);
    if (y > 0) visit(i - W, p.links[i - W] & kOpenSouth);
  }
  return reached;
}

}  // namespace

TEST_CASE("reached_from_fixed is a flood fill from the fixed and anchored pixels", "[problem]") {
  std::mt19937 rng(20261204);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long unreached = 0, reached = 0;
  // Open-link probabilities around the percolation threshold (0.5) make many components of
  // every shape: runs that overlap several runs above, U shapes that join late.
  // Rows up to 250 pixels, so that runs of more than 64 open links (a step of the vectorised scan
  // for a run's end) start at every offset; up to 1100 rows, so that the rows are walked in bands
  // of 128 or more (up to eight), whose boundaries components cross.
  for (double open : {0.2, 0.45, 0.5, 0.55, 0.8, 0.98, 0.995})
    for (double seeds : {0.0005, 0.01}) {
      const int W = 1 + int(unit(rng) * 250), H = 1 + int(unit(rng) * 1100);
      Problem p = make_open_problem(W, H, 3);
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
          const size_t i = p.index(x, y);
          p.links[i] = std::uint8_t((x + 1 < W && unit(rng) < open ? kOpenEast : 0) |
                                    (y + 1 < H && unit(rng) < open ? kOpenSouth : 0));
          const double r = unit(rng);
          if (r < seeds)
            p.fixed[i] = 1;
          else if (r < 2 * seeds)
            p.anchor_weight[i] = 0.5f;
        }
      const std::vector<std::uint8_t> expected = flood_fill(p), got = reached_from_fixed(p);
      INFO("open " << open << ", seeds " << seeds << ", " << W << " x " << H);
      REQUIRE(got.size() == expected.size());
      for (size_t i = 0; i < got.size(); ++i) {
        REQUIRE(got[i] == expected[i]);
        (got[i] ? reached : unreached) += 1;
      }
    }
  // The patterns are not all one answer.
  CHECK(reached > 1000);
  CHECK(unreached > 1000);
}
