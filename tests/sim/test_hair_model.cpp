// The procedural hair generator and the guide tools (selection, resampling).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/hair_model.hpp"
#include "sim/rng.hpp"

using namespace wisp::sim;
using Eigen::Vector3d;

namespace {

double min_root_distance(const std::vector<Vector3d>& roots) {
  double best = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < roots.size(); ++i)
    for (std::size_t j = i + 1; j < roots.size(); ++j)
      best = std::min(best, (roots[i] - roots[j]).norm());
  return best;
}

double length(const Polyline& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

}  // namespace

TEST_CASE("procedural hair: counts, roots on the scalp, clear of the head", "[sim][hair]") {
  const HeadShape head(HeadGeometry{});
  HairParams p;
  p.count = 120;
  p.segments = 16;
  for (const HairCurl style : {HairCurl::Straight, HairCurl::Wavy, HairCurl::Curly}) {
    p.style = style;
    const std::vector<Polyline> hair = generate_hair(p, head, 0.005);
    INFO(choice_name(style));
    REQUIRE(hair.size() == 120);
    for (const Polyline& s : hair) {
      REQUIRE(s.size() == 17);
      const Vector3d d = s[0].normalized();
      CHECK(std::abs(head.distance(s[0])) < 1e-9);                       // on the surface
      CHECK(std::acos(d.y()) * 180 / M_PI <= p.scalp_angle_deg + 1e-6);  // scalp region
      for (std::size_t i = 1; i < s.size(); ++i) CHECK(head.distance(s[i]) >= 0.005 - 1e-6);
      CHECK(length(s) > 0.5 * p.length);
    }
  }
}

TEST_CASE("procedural roots are spread like blue noise and depend only on the seed",
          "[sim][hair]") {
  const HeadShape head(HeadGeometry{});
  HairParams p;
  p.count = 150;
  p.segments = 4;
  const std::vector<Polyline> a = generate_hair(p, head), b = generate_hair(p, head);
  std::vector<Vector3d> roots;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i] == b[i]);
    roots.push_back(a[i][0]);
  }
  // Uniform random roots on the same region, for comparison.
  Rng rng(99);
  std::vector<Vector3d> random;
  while (random.size() < roots.size()) {
    const Vector3d d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (d.norm() > 1 || d.norm() < 1e-3) continue;
    const Vector3d u = d.normalized();
    if (std::acos(u.y()) * 180 / M_PI > p.scalp_angle_deg ||
        std::acos(u.z()) * 180 / M_PI < p.face_angle_deg)
      continue;
    random.push_back(head.surface_point(u));
  }
  const double blue = min_root_distance(roots), white = min_root_distance(random);
  std::printf("[measured] nearest-root distance: best-candidate %.4f m, uniform random %.4f m\n",
              blue, white);
  CHECK(blue > 3 * white);
  p.seed = 2;
  CHECK(generate_hair(p, head)[0][0] != a[0][0]);
}

TEST_CASE("wavy and curly styles have the requested amplitude", "[sim][hair]") {
  const HeadShape head(HeadGeometry{});
  HairParams p;
  p.count = 10;
  p.segments = 60;
  p.style = HairCurl::Curly;
  p.amplitude = 0.01;
  p.frequency = 20;  // 6 turns on 0.3 m: 10 segments per turn
  p.length_variation = 0;
  double amp = 0;
  for (const Polyline& s : generate_hair(p, head)) amp += curl_amplitude(s, 5);
  CHECK(amp / 10 == Approx(0.01).epsilon(0.25));
  p.style = HairCurl::Straight;
  amp = 0;
  for (const Polyline& s : generate_hair(p, head)) amp += curl_amplitude(s, 5);
  CHECK(amp / 10 < 0.003);
}

TEST_CASE("bad hair parameters are rejected naming the field", "[sim][hair]") {
  const HeadShape head(HeadGeometry{});
  HairParams p;
  p.count = -3;
  CHECK_THROWS_WITH(generate_hair(p, head), Catch::Contains("hair.count"));
  p = HairParams{};
  p.length = 0;
  CHECK_THROWS_WITH(generate_hair(p, head), Catch::Contains("hair.length"));
  p = HairParams{};
  p.segments = 0;
  CHECK_THROWS_WITH(generate_hair(p, head), Catch::Contains("hair.segments"));
}

TEST_CASE("resampling gives equal arc-length segments and keeps the ends", "[sim][hair]") {
  const Polyline line{{0, 0, 0}, {1, 0, 0}, {1, 3, 0}};
  const Polyline r = resample(line, 8);
  REQUIRE(r.size() == 9);
  CHECK(r.front() == line.front());
  CHECK(r.back() == line.back());
  for (std::size_t i = 1; i < r.size(); ++i) CHECK((r[i] - r[i - 1]).norm() <= 0.5 + 1e-12);
  CHECK(r[2].isApprox(Vector3d(1, 0, 0)));
}

TEST_CASE("guide selection spreads the chosen roots", "[sim][hair]") {
  // 400 strands on a line of roots: 5 guides should land evenly, ends included.
  std::vector<Polyline> strands;
  for (int i = 0; i < 400; ++i)
    strands.push_back({Vector3d(i * 0.001, 0, 0), Vector3d(i * 0.001, -1, 0)});
  std::vector<int> g = select_guides(strands, 5);
  std::sort(g.begin(), g.end());
  REQUIRE(g.size() == 5);
  CHECK(g.front() == 0);
  CHECK(g.back() == 399);
  CHECK(std::abs(g[2] - 200) <= 1);
  CHECK(select_guides(strands, 0).size() == 400);
}
