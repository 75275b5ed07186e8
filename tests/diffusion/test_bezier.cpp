// The cubic Bezier toolkit: evaluation and derivatives, splitting, bounds, flattening (adaptive
// and uniform) and paths of 3k+1 control points.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "diffusion/bezier.hpp"

using namespace wisp::diffusion;
using Eigen::Vector2d;

namespace {

// An S-shaped cubic and a loop-free hook, neither degenerate.
const Cubic kS{Vector2d(0, 0), Vector2d(10, 30), Vector2d(40, -20), Vector2d(50, 10)};
const Cubic kHook{Vector2d(-3, 2), Vector2d(8, 9), Vector2d(12, -4), Vector2d(2, -7)};

double distance_to_segment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double l = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + l * ab - p).norm();
}

// Largest distance between the curve on [u0,u1] and the chord B(u0)B(u1), sampled densely.
double chord_error(const Cubic& c, double u0, double u1) {
  double worst = 0;
  for (int j = 0; j <= 64; ++j)
    worst = std::max(
        worst, distance_to_segment(eval(c, u0 + (u1 - u0) * j / 64.0), eval(c, u0), eval(c, u1)));
  return worst;
}

}  // namespace

TEST_CASE("evaluation interpolates the end points and matches the power form", "[bezier]") {
  for (const Cubic& c : {kS, kHook}) {
    CHECK(eval(c, 0) == c[0]);
    CHECK(eval(c, 1) == c[3]);
    // B(u) = P0 + 3u(P1-P0) + 3u^2(P2-2P1+P0) + u^3(P3-3P2+3P1-P0).
    for (double u : {0.1, 0.37, 0.5, 0.81}) {
      const Vector2d power = c[0] + 3 * u * (c[1] - c[0]) + 3 * u * u * (c[2] - 2 * c[1] + c[0]) +
                             u * u * u * (c[3] - 3 * c[2] + 3 * c[1] - c[0]);
      CHECK((eval(c, u) - power).norm() < 1e-12);
    }
  }
}

TEST_CASE("derivatives agree with finite differences", "[bezier]") {
  const double h = 1e-6;
  for (const Cubic& c : {kS, kHook})
    for (double u : {0.05, 0.3, 0.5, 0.77, 0.95}) {
      const Vector2d d1 = (eval(c, u + h) - eval(c, u - h)) / (2 * h);
      const Vector2d d2 = (derivative(c, u + h) - derivative(c, u - h)) / (2 * h);
      CHECK((derivative(c, u) - d1).norm() < 1e-6 * (1 + d1.norm()));
      CHECK((second_derivative(c, u) - d2).norm() < 1e-6 * (1 + d2.norm()));
    }
  // At the ends the derivative is three times the first and last legs.
  CHECK((derivative(kS, 0) - 3 * (kS[1] - kS[0])).norm() < 1e-12);
  CHECK((derivative(kS, 1) - 3 * (kS[3] - kS[2])).norm() < 1e-12);
}

TEST_CASE("split halves reproduce the curve", "[bezier]") {
  for (const Cubic& c : {kS, kHook})
    for (double u : {0.2, 0.5, 0.73}) {
      const auto [left, right] = split(c, u);
      CHECK(left[0] == c[0]);
      CHECK(right[3] == c[3]);
      CHECK(left[3] == right[0]);
      CHECK((left[3] - eval(c, u)).norm() < 1e-12);
      for (double v : {0.0, 0.25, 0.6, 1.0}) {
        CHECK((eval(left, v) - eval(c, v * u)).norm() < 1e-11);
        CHECK((eval(right, v) - eval(c, u + v * (1 - u))).norm() < 1e-11);
      }
    }
}

TEST_CASE("subdivide gives the halves at one half", "[bezier]") {
  const auto [left, right] = subdivide(kHook);
  const auto [l2, r2] = split(kHook, 0.5);
  for (int i = 0; i < 4; ++i) {
    CHECK((left[i] - l2[i]).norm() < 1e-12);
    CHECK((right[i] - r2[i]).norm() < 1e-12);
  }
  CHECK(left[3] == right[0]);
}

TEST_CASE("the sub-cubic on [u0,u1] is that part of the curve", "[bezier]") {
  CHECK(sub_cubic(kS, 0, 1) == kS);
  const std::pair<double, double> parts[] = {{0.0, 0.4}, {0.25, 0.75}, {0.6, 1.0}, {0.1, 0.12}};
  for (const auto& [u0, u1] : parts) {
    const Cubic s = sub_cubic(kS, u0, u1);
    for (double v : {0.0, 0.3, 0.5, 1.0})
      CHECK((eval(s, v) - eval(kS, u0 + v * (u1 - u0))).norm() < 1e-10);
  }
}

TEST_CASE("reversed and straight cubics", "[bezier]") {
  const Cubic r = reversed(kHook);
  for (double u : {0.0, 0.2, 0.5, 0.9}) CHECK((eval(r, u) - eval(kHook, 1 - u)).norm() < 1e-12);
  // A line cubic runs at constant speed: its parameter is the fraction of the length.
  const Vector2d a(1, 2), b(7, -6);
  const Cubic l = line_cubic(a, b);
  for (double u : {0.0, 0.3, 0.5, 1.0}) CHECK((eval(l, u) - (a + u * (b - a))).norm() < 1e-12);
}

TEST_CASE("bounds contain the curve", "[bezier]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-50, 50);
  for (int trial = 0; trial < 20; ++trial) {
    Cubic c;
    for (Vector2d& p : c) p = Vector2d(coord(rng), coord(rng));
    const Eigen::AlignedBox2d box = bounds(c);
    for (const Vector2d& p : c) CHECK(box.contains(p));
    for (int j = 0; j <= 100; ++j) CHECK(box.contains(eval(c, j / 100.0)));
  }
}

TEST_CASE("uniform pieces stay within the tolerance", "[bezier]") {
  for (const Cubic& c : {kS, kHook})
    for (double tol : {1.0, 0.1, 0.01}) {
      const int n = flatten_pieces(c, tol, 4096);
      REQUIRE(n >= 1);
      double worst = 0;
      for (int i = 0; i < n; ++i)
        worst = std::max(worst, chord_error(c, double(i) / n, (i + 1.0) / n));
      CHECK(worst <= tol);
    }
  CHECK(flatten_pieces(kS, 1e-9, 16) == 16);  // clamped
  CHECK(flatten_pieces(line_cubic({0, 0}, {5, 5}), 0.1, 16) == 1);
  CHECK(flatten_pieces({Vector2d(0, 0), Vector2d(NAN, 0), Vector2d(1, 1), Vector2d(2, 2)}, 0.1,
                       16) == 1);
}

TEST_CASE("a path of 3k+1 points: pieces, appending, closing, evaluation", "[bezier]") {
  BezierPath path;
  CHECK(path.piece_count() == 0);
  CHECK(!path.closed());
  CHECK(eval(path, 0.5) == Vector2d::Zero());
  path.append(kS);
  CHECK(path.points.size() == 4);
  CHECK(path.piece(0) == kS);
  const Cubic next{kS[3], Vector2d(60, 40), Vector2d(70, 0), Vector2d(80, 5)};
  path.append(next);
  REQUIRE(path.piece_count() == 2);
  CHECK(path.points.size() == 7);
  CHECK(path.piece(1) == next);
  CHECK(!path.closed());
  // The parameter runs uniformly over the pieces and is clamped.
  CHECK(eval(path, 0) == kS[0]);
  CHECK(eval(path, 0.5) == next[0]);
  CHECK(eval(path, 1) == next[3]);
  CHECK(eval(path, 2) == next[3]);
  CHECK(eval(path, -1) == kS[0]);
  CHECK((eval(path, 0.25) - eval(kS, 0.5)).norm() < 1e-12);
  CHECK((eval(path, 0.9) - eval(next, 0.8)).norm() < 1e-12);
  path.append(line_cubic(next[3], kS[0]));
  CHECK(path.closed());
  // Too few points for a cubic: no pieces, evaluation gives the first point.
  const BezierPath stub{{Vector2d(3, 4), Vector2d(5, 6)}};
  CHECK(stub.piece_count() == 0);
  CHECK(eval(stub, 0.7) == Vector2d(3, 4));
}

TEST_CASE("flattening stays within tolerance and keeps the path parameter", "[bezier]") {
  const BezierPath path{{{0, 0}, {10, 30}, {40, -20}, {50, 10}, {60, 40}, {70, 0}, {80, 5}}};
  for (double tol : {0.5, 0.01}) {
    const auto poly = flatten(path, tol);
    REQUIRE(poly.size() > 4);
    CHECK(poly.front().t == 0.0);
    CHECK(poly.front().p == path.points.front());
    CHECK(poly.back().t == 1.0);
    CHECK(poly.back().p == path.points.back());
    for (size_t i = 1; i < poly.size(); ++i) {
      CHECK(poly[i].t > poly[i - 1].t);
      // Each vertex lies on the curve at its parameter, and the curve between two vertices
      // stays within the tolerance of their chord.
      CHECK((poly[i].p - eval(path, poly[i].t)).norm() < 1e-9);
      double worst = 0;
      for (int j = 0; j <= 32; ++j) {
        const double t = poly[i - 1].t + (poly[i].t - poly[i - 1].t) * j / 32.0;
        worst = std::max(worst, distance_to_segment(eval(path, t), poly[i - 1].p, poly[i].p));
      }
      CHECK(worst <= tol);
    }
  }
  CHECK(flatten(BezierPath{}, 0.1).empty());
}
