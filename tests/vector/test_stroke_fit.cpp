// Schneider's least-squares cubic fitting: the error bound, corners, loops, degenerate input.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "vector/stroke_fit.hpp"

using Eigen::Vector2d;
using wisp::diffusion::BezierPath;
using wisp::diffusion::eval;
using wisp::vector::fit_cubics;
using wisp::vector::FitOptions;

namespace {

// Distance from p to the path, by dense sampling plus a local refinement.
double distance_to_path(const BezierPath& path, const Vector2d& p) {
  const int n = 4000;
  double best = 1e300, best_s = 0;
  for (int i = 0; i <= n; ++i) {
    const double d = (eval(path, double(i) / n) - p).norm();
    if (d < best) best = d, best_s = double(i) / n;
  }
  double lo = std::max(0.0, best_s - 1.0 / n), hi = std::min(1.0, best_s + 1.0 / n);
  for (int k = 0; k < 60; ++k) {  // ternary search near the best sample
    const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
    if ((eval(path, a) - p).norm() < (eval(path, b) - p).norm())
      hi = b;
    else
      lo = a;
  }
  return std::min(best, (eval(path, 0.5 * (lo + hi)) - p).norm());
}

// Distance from p to a polyline.
double distance_to_polyline(const std::vector<Vector2d>& poly, const Vector2d& p) {
  double best = 1e300;
  for (size_t i = 0; i + 1 < poly.size(); ++i) {
    const Vector2d d = poly[i + 1] - poly[i];
    const double f =
        d.squaredNorm() > 0 ? std::clamp((p - poly[i]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (poly[i] + f * d - p).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("fitted cubics pass within the tolerance of every input point", "[vector][fit]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (double tol : {0.05, 0.2, 1.0}) {
    for (int trial = 0; trial < 12; ++trial) {
      // A wavy curve with random harmonics, densely sampled.
      const double a1 = 40 * U(rng), a2 = 15 * U(rng), f1 = 1 + 2 * std::abs(U(rng)),
                   f2 = 3 + 4 * std::abs(U(rng));
      std::vector<Vector2d> pts;
      for (int i = 0; i <= 300; ++i) {
        const double x = i * 1.0;
        pts.emplace_back(x, 100 + a1 * std::sin(f1 * x / 50) + a2 * std::sin(f2 * x / 50 + 1));
      }
      FitOptions o;
      o.tolerance = tol;
      const auto fit = fit_cubics(pts, o);
      INFO("tolerance " << tol << " trial " << trial << " cubics " << fit.piece_count());
      REQUIRE(fit.piece_count() >= 1);
      REQUIRE(fit.param.size() == pts.size());
      CHECK(fit.points.front() == pts.front());
      CHECK(fit.points.back() == pts.back());
      double worst_at_param = 0, worst_distance = 0, worst_back = 0;
      for (size_t i = 0; i < pts.size(); ++i) {
        worst_at_param = std::max(worst_at_param, (eval(fit, fit.param[i]) - pts[i]).norm());
        if (i % 7 == 0) worst_distance = std::max(worst_distance, distance_to_path(fit, pts[i]));
        if (i > 0) CHECK(fit.param[i] >= fit.param[i - 1]);
      }
      // And the path stays near the polyline between the points (no overshoot).
      for (int i = 0; i <= 600; ++i)
        worst_back = std::max(worst_back, distance_to_polyline(pts, eval(fit, i / 600.0)));
      CHECK(worst_at_param <= tol * (1 + 1e-9));
      CHECK(worst_distance <= tol * (1 + 1e-9));
      CHECK(worst_back <= tol + 0.01);
      // Compression: far fewer cubics than segments.
      if (tol >= 0.2) CHECK(fit.piece_count() < 30);
    }
  }
}

TEST_CASE("points of one cubic are fitted by one cubic", "[vector][fit]") {
  const wisp::diffusion::Cubic c{Vector2d(0, 0), Vector2d(30, 80), Vector2d(90, -40),
                                 Vector2d(120, 30)};
  std::vector<Vector2d> pts;
  for (int i = 0; i <= 100; ++i) pts.push_back(eval(c, i / 100.0));
  FitOptions o;
  o.tolerance = 0.05;
  const auto fit = fit_cubics(pts, o);
  CHECK(fit.piece_count() == 1);
}

TEST_CASE("corners are kept as knots, loops close, degenerate input is safe", "[vector][fit]") {
  FitOptions o;
  o.tolerance = 0.1;
  // An L: the corner is a knot, each arm a straight cubic.
  std::vector<Vector2d> l;
  for (int i = 0; i <= 20; ++i) l.emplace_back(i, 0);
  for (int i = 1; i <= 20; ++i) l.emplace_back(20, i);
  auto fit = fit_cubics(l, o);
  CHECK(fit.piece_count() == 2);
  CHECK((fit.points[3] - Vector2d(20, 0)).norm() < 1e-12);
  CHECK(!fit.closed());

  // A circle as a loop: closed path, every point within the tolerance.
  std::vector<Vector2d> circle;
  for (int i = 0; i < 120; ++i)
    circle.emplace_back(50 + 30 * std::cos(2 * M_PI * i / 120),
                        50 + 30 * std::sin(2 * M_PI * i / 120));
  fit = fit_cubics(circle, o, true);
  REQUIRE(fit.piece_count() >= 2);
  CHECK(fit.closed());
  for (size_t i = 0; i < circle.size(); ++i)
    CHECK((eval(fit, fit.param[i]) - circle[i]).norm() <= 0.1 + 1e-9);

  // Duplicates, two points, one point.
  fit = fit_cubics({Vector2d(1, 1), Vector2d(1, 1), Vector2d(5, 1), Vector2d(5, 1)}, o);
  CHECK(fit.piece_count() == 1);
  CHECK(fit.param == std::vector<double>{0, 0, 1, 1});
  CHECK(fit_cubics({Vector2d(1, 1), Vector2d(1, 1)}, o).piece_count() == 0);
  CHECK(!fit_cubics({Vector2d(1, 1), Vector2d(5, 1)}, o, true).closed());  // a "loop" of two
  CHECK(fit_cubics({Vector2d(1, 1)}, o).piece_count() == 0);
}
