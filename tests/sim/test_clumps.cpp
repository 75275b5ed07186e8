// Dense grooms to guides (sim/clumps.hpp): clustering a generated groom of 20 000 strands of 30
// points, the clump widths, and the grid behind both searches (sim/point_grid.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "sim/clumps.hpp"
#include "sim/point_grid.hpp"
#include "sim/rng.hpp"

using namespace wisp::sim;
using Eigen::Vector3d;

namespace {

// The procedural generator's wavy shoulder-length hair at 20 000 strands of 30 points.
const std::vector<Polyline>& dense_groom() {
  static const std::vector<Polyline> groom = [] {
    HairParams p;
    p.count = 20000;
    p.segments = 29;
    return generate_hair(p, HeadShape(HeadGeometry{}));
  }();
  return groom;
}

std::vector<std::vector<int>> members_of(const Clumps& c) {
  std::vector<std::vector<int>> m(c.guide.size());
  for (std::size_t i = 0; i < c.clump_of.size(); ++i) m[c.clump_of[i]].push_back(int(i));
  return m;
}

// The fraction of the members' samples inside the clump's tube: nearer the guide than half the
// width there (linear between guide samples, as the wisp's monotone interpolation bounds it).
double covered(const Polyline& guide, const std::vector<double>& width,
               const std::vector<Polyline>& strands, const std::vector<int>& members) {
  int inside = 0, total = 0;
  for (int m : members)
    for (const Vector3d& p : strands[m]) {
      bool in = false;
      for (std::size_t k = 0; k + 1 < guide.size() && !in; ++k) {
        const Vector3d e = guide[k + 1] - guide[k];
        const double t = std::clamp((p - guide[k]).dot(e) / e.squaredNorm(), 0.0, 1.0);
        const double half = 0.5 * ((1 - t) * width[k] + t * width[k + 1]);
        in = (p - (guide[k] + t * e)).norm() <= half + 1e-12;
      }
      inside += in;
      ++total;
    }
  return double(inside) / total;
}

// Sum over strands of the squared feature distance to their guide's, as the clustering sees it.
double clustering_cost(const std::vector<Polyline>& strands, const Clumps& c) {
  double cost = 0;
  for (std::size_t i = 0; i < strands.size(); ++i) {
    const Polyline a = resample(strands[i], 3), b = resample(strands[c.guide[c.clump_of[i]]], 3);
    for (int k = 0; k < 4; ++k) cost += (k == 0 ? 4.0 : 1.0) * (a[k] - b[k]).squaredNorm();
  }
  return cost;
}

}  // namespace

TEST_CASE("the point grid finds the same nearest point as a scan of all points", "[sim][clumps]") {
  Rng rng(3);
  std::vector<Vector3d> points;
  const Eigen::AlignedBox3d box(Vector3d(-1, -0.5, 0), Vector3d(1, 0.5, 0.2));
  PointGrid grid(box, 0.05);
  for (int i = 0; i < 2000; ++i) {
    points.emplace_back(rng.uniform(-1, 1), rng.uniform(-0.5, 0.5), rng.uniform(0, 0.2));
    grid.insert(points.back(), i);
  }
  for (int q = 0; q < 500; ++q) {
    // Queries inside and outside the box.
    const Vector3d p(rng.uniform(-1.5, 1.5), rng.uniform(-1, 1), rng.uniform(-0.5, 0.5));
    double scan = std::numeric_limits<double>::max();
    for (const Vector3d& x : points) scan = std::min(scan, (p - x).squaredNorm());
    double found = std::numeric_limits<double>::max();
    int visited = 0;
    grid.search(
        p,
        [&](int, const Vector3d& x) {
          ++visited;
          found = std::min(found, (p - x).squaredNorm());
        },
        [&] { return found; });
    REQUIRE(found == scan);
    CHECK(visited < 2000);
  }
}

TEST_CASE("a dense groom: guides are strands of the model, each strand in exactly one clump",
          "[sim][clumps]") {
  const std::vector<Polyline>& groom = dense_groom();
  ClumpOptions o;
  o.count = 150;
  const Clumps c = cluster_strands(groom, o);
  REQUIRE(c.guide.size() == 150);
  REQUIRE(c.clump_of.size() == groom.size());
  std::vector<int> sorted = c.guide;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());  // distinct strands
  std::vector<int> size(c.guide.size(), 0);
  for (int k : c.clump_of) {
    REQUIRE(k >= 0);
    REQUIRE(k < int(c.guide.size()));
    ++size[k];
  }
  for (std::size_t k = 0; k < c.guide.size(); ++k) {
    REQUIRE(c.guide[k] >= 0);
    REQUIRE(c.guide[k] < int(groom.size()));
    CHECK(c.clump_of[c.guide[k]] == int(k));  // a guide belongs to its own clump
  }
  std::printf("[measured] clump sizes of 20000 strands in 150 clumps: %d to %d\n",
              *std::min_element(size.begin(), size.end()),
              *std::max_element(size.begin(), size.end()));
  CHECK(*std::min_element(size.begin(), size.end()) >= 1);
}

TEST_CASE("clustering is deterministic in its seed and the rounds improve on the seeds",
          "[sim][clumps]") {
  const std::vector<Polyline>& groom = dense_groom();
  ClumpOptions o;
  o.count = 120;
  const Clumps a = cluster_strands(groom, o), b = cluster_strands(groom, o);
  CHECK(a.guide == b.guide);
  CHECK(a.clump_of == b.clump_of);
  o.seed = 2;
  CHECK(cluster_strands(groom, o).guide != a.guide);
  o.seed = 1;
  o.rounds = 0;  // the k-means++ seeds with their nearest strands
  const double seeded = clustering_cost(groom, cluster_strands(groom, o));
  const double refined = clustering_cost(groom, a);
  std::printf("[measured] clustering cost: seeds %.4g, after rounds %.4g\n", seeded, refined);
  CHECK(refined < 0.9 * seeded);
}

TEST_CASE("clump widths cover 95 % of each clump's strand samples", "[sim][clumps]") {
  const std::vector<Polyline>& groom = dense_groom();
  ClumpOptions o;
  o.count = 150;
  const Clumps c = cluster_strands(groom, o);
  const std::vector<std::vector<int>> members = members_of(c);
  double worst = 1, widest = 0;
  for (std::size_t k = 0; k < c.guide.size(); ++k) {
    // As the simulation takes it: the medoid resampled to 24 segments.
    const Polyline guide = resample(groom[c.guide[k]], 24);
    const std::vector<double> width = clump_width(guide, groom, members[k]);
    REQUIRE(width.size() == guide.size());
    for (double w : width) CHECK(w >= 0.002);
    widest = std::max(widest, *std::max_element(width.begin(), width.end()));
    const double f = covered(guide, width, groom, members[k]);
    worst = std::min(worst, f);
    CHECK(f >= 0.95);
  }
  std::printf("[measured] least covered clump: %.3f of its samples; widest clump %.3f m\n", worst,
              widest);
  // A lone strand is as wide as the floor.
  const std::vector<double> lone = clump_width(groom[0], groom, {0}, 0.98, 0.003);
  CHECK(*std::max_element(lone.begin(), lone.end()) == 0.003);
}

TEST_CASE("clustering: as many clumps as strands keeps every strand, bad input is refused",
          "[sim][clumps]") {
  const std::vector<Polyline> three = {{Vector3d(0, 0, 0), Vector3d(0, -1, 0)},
                                       {Vector3d(1, 0, 0), Vector3d(1, -1, 0)},
                                       {Vector3d(2, 0, 0), Vector3d(2, -1, 0)}};
  ClumpOptions o;
  o.count = 5;
  const Clumps all = cluster_strands(three, o);
  CHECK(all.guide == std::vector<int>{0, 1, 2});
  o.count = 2;
  CHECK(cluster_strands(three, o).guide.size() == 2);
  // Duplicated strands: fewer distinct clumps than asked for, never an empty one.
  const std::vector<Polyline> same(10, three[0]);
  const Clumps dup = cluster_strands(same, o);
  CHECK(dup.guide.size() == 1);
  CHECK(std::all_of(dup.clump_of.begin(), dup.clump_of.end(), [](int k) { return k == 0; }));
  CHECK_THROWS(cluster_strands({}, o));
  CHECK_THROWS(cluster_strands({{Vector3d::Zero()}}, o));
  o.count = 0;
  CHECK_THROWS(cluster_strands(three, o));
}
