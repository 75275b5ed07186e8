// The exact cross-check: the wisp outlines as rational cubic Bezier curves in CGAL's Bezier
// traits (intersection points are algebraic numbers, CORE). Its own library (wisp_vector_exact),
// because it compiles slowly and rendering never needs it: tests compare its face count with the
// segment arrangement, the benchmark times it.
#include <CGAL/Arr_Bezier_curve_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/CORE_algebraic_number_traits.h>
#include <CGAL/Cartesian.h>

#include <stdexcept>

#include "diffusion/timer.hpp"
#include "vector/arrangement.hpp"

namespace wisp::vector {

namespace {

using NtTraits = CGAL::CORE_algebraic_number_traits;
using Rational = NtTraits::Rational;
using RatKernel = CGAL::Cartesian<Rational>;
using AlgKernel = CGAL::Cartesian<NtTraits::Algebraic>;
using RatPoint = RatKernel::Point_2;
using BezierTraits = CGAL::Arr_Bezier_curve_traits_2<RatKernel, AlgKernel, NtTraits>;
using BezierArrangement = CGAL::Arrangement_2<BezierTraits>;

RatPoint rational(const Eigen::Vector2d& p) {
  return RatPoint(Rational(p.x()), Rational(p.y()));
}

}  // namespace

ExactTopology exact_bezier_topology(const std::vector<Wisp>& wisps) {
  const auto t0 = diffusion::Clock::now();
  std::vector<BezierTraits::Curve_2> curves;
  for (const Wisp& w : wisps) {
    for (int i = 0; i < w.outline.piece_count(); ++i) {
      const diffusion::Cubic c = w.outline.piece(i);
      if (c[0] == c[3] && c[1] == c[0] && c[2] == c[0]) continue;
      // Caps are straight: give them as degree 1 (collinear cubics are a fragile case).
      std::vector<RatPoint> control;
      if (w.outline.side[i] == Side::Tip || w.outline.side[i] == Side::Root)
        control = {rational(c[0]), rational(c[3])};
      else
        control = {rational(c[0]), rational(c[1]), rational(c[2]), rational(c[3])};
      curves.emplace_back(control.begin(), control.end());
    }
  }
  BezierArrangement arr;
  try {
    CGAL::insert(arr, curves.begin(), curves.end());
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("exact Bezier arrangement failed: ") + e.what());
  }
  ExactTopology t;
  t.vertices = long(arr.number_of_vertices());
  t.edges = long(arr.number_of_edges());
  t.faces = long(arr.number_of_faces());
  t.ms = diffusion::ms_since(t0);
  return t;
}

}  // namespace wisp::vector
