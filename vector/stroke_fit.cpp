// Schneider's least-squares cubic fitting (see stroke_fit.hpp).
#include "vector/stroke_fit.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::vector {

using diffusion::Cubic;
using diffusion::derivative;
using diffusion::eval;
using diffusion::second_derivative;
using Eigen::Vector2d;

namespace {

Vector2d unit_or(const Vector2d& v, const Vector2d& fallback) {
  const double n = v.norm();
  return n > 1e-12 ? Vector2d(v / n) : fallback;
}

// Fits p[a..b] (at least two points) and appends the cubics to the path and each point's local
// parameter.
class Fitter {
 public:
  Fitter(const std::vector<Vector2d>& p, const FitOptions& o)
      : p_(p), tol2_(o.tolerance * o.tolerance), o_(o) {}

  // Parameters per input point (global cubic index + local u, later normalised).
  std::vector<double> u_global;
  diffusion::BezierPath out;
  std::vector<int> knots;

  void fit(int a, int b, const Vector2d& t1, const Vector2d& t2) {
    const int n = b - a + 1;
    if (n == 2) {
      const double d = (p_[b] - p_[a]).norm() / 3.0;
      emit(a, b, {p_[a], p_[a] + t1 * d, p_[b] + t2 * d, p_[b]}, {0.0, 1.0});
      return;
    }
    std::vector<double> u = chord_parameters(a, b);
    Cubic c = generate(a, b, u, t1, t2);
    int split = 0;
    double err = max_error(a, b, c, u, &split);
    if (err <= tol2_) return emit(a, b, c, u);
    // Chord-length parameters are only a start: unless the cubic is hopeless (off by a quarter of
    // the chord), improve them while the error keeps falling.
    const double chord2 = (p_[b] - p_[a]).squaredNorm();
    if (err <= std::max(16 * tol2_, chord2 / 16)) {
      for (int it = 0; it < o_.max_reparameterize; ++it) {
        std::vector<double> u2 = u;
        reparameterize(a, b, c, u2);
        const Cubic c2 = generate(a, b, u2, t1, t2);
        int split2 = 0;
        const double err2 = max_error(a, b, c2, u2, &split2);
        if (err2 >= err) break;
        u = std::move(u2), c = c2, err = err2, split = split2;
        if (err <= tol2_) return emit(a, b, c, u);
      }
    }
    const Vector2d fallback = unit_or(p_[b] - p_[a], Vector2d(1, 0));
    const Vector2d tc = unit_or(p_[split + 1] - p_[split - 1], fallback);
    fit(a, split, t1, -tc);
    fit(split, b, tc, t2);
  }

 private:
  void emit(int a, int b, const Cubic& c, const std::vector<double>& u) {
    const int k = int(knots.size()) - 1;  // index of this cubic
    out.append(c);
    for (int i = a; i <= b; ++i) {
      double v = std::clamp(u[i - a], 0.0, 1.0);
      if (i == a) v = 0;
      if (i == b) v = 1;
      // The point shared by two cubics keeps the parameter of the first (end of cubic k).
      if (i == a && i < int(u_global.size()) && u_global[i] >= 0) continue;
      u_global[i] = k + v;
    }
    knots.push_back(b);
  }

  std::vector<double> chord_parameters(int a, int b) const {
    std::vector<double> u(b - a + 1, 0.0);
    for (int i = a + 1; i <= b; ++i) u[i - a] = u[i - a - 1] + (p_[i] - p_[i - 1]).norm();
    const double len = u.back();
    for (double& v : u) v = len > 0 ? v / len : 0;
    return u;
  }

  // The least-squares cubic with fixed ends and tangent directions (Schneider's GenerateBezier).
  Cubic generate(int a, int b, const std::vector<double>& u, const Vector2d& t1,
                 const Vector2d& t2) const {
    const Vector2d p0 = p_[a], p3 = p_[b];
    double c00 = 0, c01 = 0, c11 = 0, x0 = 0, x1 = 0;
    for (int i = a; i <= b; ++i) {
      const double t = u[i - a], s = 1 - t;
      const double b0 = s * s * s, b1 = 3 * t * s * s, b2 = 3 * t * t * s, b3 = t * t * t;
      const Vector2d a0 = t1 * b1, a1 = t2 * b2;
      c00 += a0.dot(a0);
      c01 += a0.dot(a1);
      c11 += a1.dot(a1);
      const Vector2d tmp = p_[i] - (p0 * (b0 + b1) + p3 * (b2 + b3));
      x0 += a0.dot(tmp);
      x1 += a1.dot(tmp);
    }
    const double det = c00 * c11 - c01 * c01;
    const double seg = (p3 - p0).norm();
    double arc = 0;
    for (int i = a + 1; i <= b; ++i) arc += (p_[i] - p_[i - 1]).norm();
    double alpha1 = 0, alpha2 = 0;
    if (std::abs(det) > 1e-12 * std::max(1.0, c00 * c11)) {
      alpha1 = (x0 * c11 - x1 * c01) / det;
      alpha2 = (c00 * x1 - c01 * x0) / det;
    }
    // Degenerate or reversed tangents: Wu and Barsky's heuristic (a third of the chord). Handles
    // longer than the input itself overshoot between the points (few points, inconsistent
    // tangents): the same.
    const double eps = 1e-6 * seg;
    if (!(alpha1 > eps) || !(alpha2 > eps) || !std::isfinite(alpha1) || !std::isfinite(alpha2) ||
        alpha1 > arc || alpha2 > arc)
      alpha1 = alpha2 = seg / 3;
    return {p0, p0 + t1 * alpha1, p3 + t2 * alpha2, p3};
  }

  // Largest squared distance between a point and its place on the cubic; `split` is the worst
  // interior point.
  // Between two points, the cubic at the middle parameter must stay near their segment too, or a
  // cubic could pass every point and still loop away between them.
  double max_error(int a, int b, const Cubic& c, const std::vector<double>& u, int* split) const {
    double worst = 0;
    *split = (a + b) / 2;
    for (int i = a + 1; i < b; ++i) {
      const double d = (eval(c, u[i - a]) - p_[i]).squaredNorm();
      if (d >= worst) {
        worst = d;
        *split = i;
      }
    }
    for (int i = a; i < b; ++i) {
      const Vector2d m = eval(c, 0.5 * (u[i - a] + u[i + 1 - a]));
      const Vector2d d = p_[i + 1] - p_[i];
      const double f =
          d.squaredNorm() > 0 ? std::clamp((m - p_[i]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const double e = 0.25 * (p_[i] + f * d - m).squaredNorm();  // counts at half weight
      if (e > worst) {
        worst = e;
        *split = std::clamp(i - a < (b - a) / 2 ? i + 1 : i, a + 1, b - 1);
      }
    }
    return worst;
  }

  void reparameterize(int a, int b, const Cubic& c, std::vector<double>& u) const {
    for (int i = a + 1; i < b; ++i) {
      double& t = u[i - a];
      const Vector2d d = eval(c, t) - p_[i];
      const Vector2d d1 = derivative(c, t), d2 = second_derivative(c, t);
      const double num = d.dot(d1), den = d1.dot(d1) + d.dot(d2);
      if (std::abs(den) > 1e-12) t = std::clamp(t - num / den, 0.0, 1.0);
    }
  }

  const std::vector<Vector2d>& p_;
  double tol2_;
  const FitOptions& o_;
};

double turning_deg(const Vector2d& in, const Vector2d& out) {
  const double c = in.dot(out) / std::max(1e-300, in.norm() * out.norm());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

// Tangent at p[i] towards p[j] and p[k] (in that order away from i): the derivative at i of the
// parabola through the three points with chord-length knots (exact for smooth input sampled
// densely); the chord to p[j] when the spacing is very uneven.
Vector2d end_tangent(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const double h1 = (b - a).norm(), h2 = (c - b).norm();
  const Vector2d chord = unit_or(b - a, Vector2d(1, 0));
  if (h1 <= 0 || h2 <= 0 || h2 > 4 * h1 || h1 > 4 * h2) return chord;
  const Vector2d d = (b - a) * ((h1 + h2) / (h1 * h2)) - (c - a) * (h1 / (h2 * (h1 + h2)));
  const Vector2d t = unit_or(d, chord);
  return t.dot(chord) > 0.5 ? t : chord;
}

// Direction from p[i] towards later points, skipping points nearer than `reach` (exact input has
// tiny segments near arrangement vertices whose direction is not the curve's).
Vector2d forward_tangent(const std::vector<Vector2d>& p, int i, int last, double reach) {
  int j = i + 1;
  while (j < last && (p[j] - p[i]).norm() < reach) ++j;
  if (j + 1 <= last) return end_tangent(p[i], p[j], p[j + 1]);
  return unit_or(p[j] - p[i], Vector2d(1, 0));
}
Vector2d backward_tangent(const std::vector<Vector2d>& p, int i, int first, double reach) {
  int j = i - 1;
  while (j > first && (p[j] - p[i]).norm() < reach) --j;
  if (j - 1 >= first) return end_tangent(p[i], p[j], p[j - 1]);
  return unit_or(p[j] - p[i], Vector2d(-1, 0));
}

}  // namespace

FittedPath fit_cubics(const std::vector<Vector2d>& input, const FitOptions& options, bool closed) {
  FittedPath out;
  // Distinct points, remembering which distinct point each input point became.
  std::vector<Vector2d> p;
  std::vector<int> rep(input.size());
  for (size_t i = 0; i < input.size(); ++i) {
    if (p.empty() || (input[i] - p.back()).norm() > 1e-9) p.push_back(input[i]);
    rep[i] = int(p.size()) - 1;
  }
  if (closed && p.size() > 2 && (p.back() - p.front()).norm() <= 1e-9) {
    p.pop_back();
    for (int& r : rep) r = r == int(p.size()) ? 0 : r;
  }
  if (p.size() < 2) return out;
  if (p.size() == 2) closed = false;

  const int m = int(p.size());
  auto corner_at = [&](int i) {
    const Vector2d before = p[i] - p[(i + m - 1) % m], after = p[(i + 1) % m] - p[i];
    return turning_deg(before, after) > options.corner_deg;
  };
  // A loop starts at its sharpest corner (or at point 0) and ends there again.
  int start = 0;
  if (closed) {
    double sharpest = options.corner_deg;
    for (int i = 0; i < m; ++i) {
      const double a = turning_deg(p[i] - p[(i + m - 1) % m], p[(i + 1) % m] - p[i]);
      if (a > sharpest) sharpest = a, start = i;
    }
  }
  std::vector<Vector2d> q;  // the points in fitting order (a loop repeats its start at the end)
  for (int i = 0; i < m; ++i) q.push_back(p[(start + i) % m]);
  if (closed) q.push_back(q.front());
  const int last = int(q.size()) - 1;

  std::vector<int> cuts = {0};
  for (int i = 1; i < last; ++i)
    if (corner_at((start + i) % m)) cuts.push_back(i);
  cuts.push_back(last);

  const double reach = std::max(0.5, 2 * options.tolerance);
  Fitter fitter(q, options);
  fitter.u_global.assign(q.size(), -1.0);
  fitter.knots.push_back(0);
  const bool smooth_loop = closed && !corner_at(start);
  Vector2d loop_tangent(1, 0);
  if (smooth_loop) loop_tangent = unit_or(q[1] - q[last - 1], Vector2d(1, 0));
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const int a = cuts[c], b = cuts[c + 1];
    Vector2d t1 = forward_tangent(q, a, b, reach), t2 = backward_tangent(q, b, a, reach);
    if (smooth_loop && a == 0) t1 = loop_tangent;
    if (smooth_loop && b == last) t2 = -loop_tangent;
    fitter.fit(a, b, t1, t2);
  }

  out.points = std::move(fitter.out.points);
  const int k = out.piece_count();
  std::vector<double> s(q.size());
  for (size_t i = 0; i < q.size(); ++i) s[i] = std::max(0.0, fitter.u_global[i]) / k;
  for (size_t i = 1; i < s.size(); ++i) s[i] = std::max(s[i], s[i - 1]);
  out.knot_index.clear();
  for (int kn : fitter.knots) out.knot_index.push_back(closed ? (start + kn) % m : kn);

  // Back to the input's order and duplicates.
  std::vector<double> s_distinct(m);
  for (int i = 0; i < m; ++i) s_distinct[(start + i) % m] = s[i];
  out.param.resize(input.size());
  for (size_t i = 0; i < input.size(); ++i) out.param[i] = s_distinct[rep[i]];
  // Knot indices from distinct points back to the first input point of each.
  std::vector<int> first_input(m, -1);
  for (size_t i = 0; i < input.size(); ++i)
    if (first_input[rep[i]] < 0) first_input[rep[i]] = int(i);
  for (int& kn : out.knot_index) kn = first_input[kn];
  return out;
}

}  // namespace wisp::vector
