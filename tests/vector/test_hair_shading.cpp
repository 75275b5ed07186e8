// Light on wisps: the tube model's closed forms, which side of a wisp is lit, toon band edges
// inside their wisp and only where it shows, the highlight band where the analytic
// Kajiya-Kay peak is, measured on the solved image, and the anime band on the head, one crisp
// shape across neighbouring wisps.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>

#include "diffusion/multigrid.hpp"
#include "diffusion/rasterize.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_curves.hpp"
#include "vector/hair_shading.hpp"
#include "vector/highlights.hpp"
#include "vector/stroke_fit.hpp"
#include "vector/wisp_chart.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
namespace v = wisp::vector;

namespace {

// A pinhole camera at the origin looking down -z, image x right, y down.
struct Camera {
  double f = 300;
  Vector2d c{128, 128};
  Vector2d project(const Vector3d& p) const {
    return {c.x() + f * p.x() / -p.z(), c.y() - f * p.y() / -p.z()};
  }
};

wisp::sim::ProjectedStrand strand_of(int id, const std::vector<Vector3d>& world,
                                     const Camera& cam) {
  wisp::sim::ProjectedStrand s;
  s.id = id;
  for (size_t i = 0; i < world.size(); ++i) {
    s.world.push_back(world[i]);
    s.pixel.push_back(cam.project(world[i]));
    s.depth.push_back(world[i].norm());
    const Vector3d d = world[std::min(i + 1, world.size() - 1)] - world[i > 0 ? i - 1 : 0];
    s.tangent.push_back(d.normalized());
    s.visible.push_back(1);
  }
  return s;
}

wisp::sim::ProjectedFrame frame_of(std::vector<wisp::sim::ProjectedStrand> strands,
                                   const Vector3d& light, const Camera& cam) {
  wisp::sim::ProjectedFrame f;
  f.width = f.height = 256;
  f.focal_px = cam.f;
  f.eye = Vector3d::Zero();
  f.light_dir = light.normalized();
  f.strands = std::move(strands);
  return f;
}

v::HairStyle lit_style() {
  v::HairStyle s;
  s.geometry.width = 0.06;
  s.geometry.profile = v::WidthProfile::constant();
  s.shading.model = v::ShadingModel::Lit;
  s.shading.lighting.head_shadow = 0;  // one strand: no head to shadow it
  s.shading.lighting.specular = 0;
  s.hair = {0.9f, 0.6f, 0.3f};
  s.shadow = {0.1f, 0.05f, 0.05f};
  return s;
}

struct Rendered {
  std::vector<v::Wisp> wisps;
  v::WispArrangement arrangement;
  v::HairCurves curves;
  std::vector<float> rgb;  // planes
  Eigen::Vector3f at(int x, int y) const {
    const size_t n = 256 * 256, i = size_t(y) * 256 + x;
    return {rgb[i], rgb[n + i], rgb[2 * n + i]};
  }
};

Rendered render(const wisp::sim::ProjectedFrame& frame, const v::HairStyle& style) {
  Rendered r;
  r.wisps = v::build_wisps(frame, style.geometry);
  v::ArrangementOptions o;
  o.view = v::image_rect(256, 256);
  o.keep_faces = true;
  r.arrangement = v::build_arrangement(r.wisps, o);
  r.curves = v::shade_hair(frame, r.wisps, r.arrangement, style);
  for (const auto& c : r.curves.curves) wisp::diffusion::validate(c, "curve");
  const auto problem = wisp::diffusion::rasterize(r.curves.curves, 256, 256);
  r.rgb = wisp::diffusion::solve_multigrid(problem, {}, nullptr).planes;
  return r;
}

bool inside_outline(const v::Wisp& w, const Vector2d& p, double tolerance) {
  const auto poly = v::outline_polygon(w);
  bool in = false;
  double best = 1e300;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vector2d a = poly[i].p, b = poly[j].p;
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
    const Vector2d d = b - a;
    const double f =
        d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0;
    best = std::min(best, (a + f * d - p).norm());
  }
  return in || best <= tolerance;
}

}  // namespace

TEST_CASE("the tube frame and its closed forms", "[vector][shading]") {
  std::mt19937 rng(3);
  std::normal_distribution<double> N01;
  const auto random_unit = [&] { return Vector3d(N01(rng), N01(rng), N01(rng)).normalized(); };
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d T = random_unit(), V = random_unit(), L = random_unit();
    const v::TubeFrame f = v::tube_frame(T, V);
    CHECK(std::abs(f.B.dot(T)) < 1e-9);
    CHECK(std::abs(f.B.dot(V)) < 1e-9);
    CHECK(std::abs(f.C.dot(T)) < 1e-9);
    for (double u : {-1.0, -0.3, 0.0, 0.7, 1.0}) CHECK(v::tube_normal(f, u).norm() == Approx(1));
    CHECK(std::abs(v::tube_normal(f, 1).dot(V)) < 1e-9);  // the outline is the tube's silhouette
    CHECK(std::abs(v::tube_normal(f, -1).dot(V)) < 1e-9);
    // Iso-lines of N.L and the peak, against a dense scan.
    double best = -2, best_u = 0;
    for (int i = 0; i <= 20000; ++i) {
      const double u = -1 + i / 10000.0, d = v::tube_normal(f, u).dot(L);
      if (d > best) best = d, best_u = u;
    }
    CHECK(v::lambert_peak_u(f, L) == Approx(best_u).margin(2e-3));
    const double k = 0.5 * best + 0.1 * N01(rng);
    for (double u : v::lambert_iso_u(f, L, k))
      CHECK(v::tube_normal(f, u).dot(L) == Approx(k).margin(1e-9));
    // The Blinn term's peak across the tube is the Kajiya-Kay value: max_u N.H = sin(T, H).
    double blinn_max = 0;
    for (int i = 0; i <= 4000; ++i)
      blinn_max = std::max(blinn_max, v::blinn(v::tube_normal(f, -1 + i / 2000.0), L, V, 1));
    const Vector3d H = (L + V).normalized();
    if (f.C.dot(H) > 0) CHECK(blinn_max == Approx(v::kajiya_kay_specular(T, L, V, 1)).margin(1e-4));
  }
  CHECK(v::depth_detail(1.0, 1.0, 2.0) == 1.0);
  CHECK(v::depth_detail(2.0, 1.0, 2.0) == Approx(0.0).margin(1e-12));
  CHECK(v::depth_detail(std::sqrt(2.0), 1.0, 2.0) == Approx(0.5));
}

TEST_CASE("u = +1 is the wisp's on-screen Left side, where B points", "[vector][shading]") {
  const Camera cam;
  std::vector<Vector3d> world;
  for (int i = 0; i <= 10; ++i)
    world.emplace_back(0.05 * std::sin(i * 0.4), 0.25 - 0.05 * i, -1.0 - 0.02 * i);
  const auto frame = frame_of({strand_of(0, world, cam)}, Vector3d(1, 0, 1), cam);
  const auto style = lit_style();
  const auto wisps = v::build_wisps(frame, style.geometry);
  REQUIRE(wisps.size() == 1);
  const v::WispChart chart(wisps[0], frame.strands[0], frame.eye);
  for (double t : {0.1, 0.5, 0.9}) {
    const Vector2d c = chart.point(t, 0), left = chart.point(t, 1);
    // The lateral axis B, projected, points to the chart's u = +1 side.
    const v::TubeFrame f = chart.frame(t);
    const Vector2d b_px = cam.project(chart.world(t) + 1e-4 * f.B) - cam.project(chart.world(t));
    CHECK(b_px.dot(left - c) > 0);
    // And that side is the outline's Left side (Side::Left: (d.y, -d.x) for travel d).
    const Vector2d d = chart.point(t + 0.01, 0) - chart.point(t - 0.01, 0);
    CHECK(Vector2d(d.y(), -d.x()).dot(left - c) > 0);
  }
}

TEST_CASE("the side of a wisp facing the light is the bright one", "[vector][shading]") {
  const Camera cam;
  std::vector<Vector3d> world;
  for (int i = 0; i <= 8; ++i) world.emplace_back(0, 0.2 - 0.05 * i, -1.0);  // straight down
  // Travelling down the screen, the on-screen Left side is image right: +x in the world.
  for (double side : {1.0, -1.0}) {
    const auto frame = frame_of({strand_of(0, world, cam)}, Vector3d(side, 0, 0.4), cam);
    v::HairStyle style = lit_style();
    style.shading.lighting.ambient = style.shading.lighting.kajiya_diffuse = 0.1;
    style.shading.lighting.lambert = 0.8;
    const Rendered r = render(frame, style);
    double right = 0, left = 0;
    for (int y = 110; y < 150; ++y) {
      right += r.at(128 + 4, y).sum();
      left += r.at(128 - 5, y).sum();
    }
    INFO("light from " << (side > 0 ? "+x" : "-x") << ": right " << right << " left " << left);
    CHECK((side > 0 ? right > 1.3 * left : left > 1.3 * right));
  }
}

TEST_CASE("hard band edges lie inside their wisp, carry both bands and only show where it does",
          "[vector][shading]") {
  const Camera cam;
  // Two crossing strands, the second nearer the eye.
  std::vector<Vector3d> a, b;
  for (int i = 0; i <= 10; ++i) a.emplace_back(-0.12 + 0.024 * i, 0.2 - 0.04 * i, -1.0);
  for (int i = 0; i <= 10; ++i) b.emplace_back(0.12 - 0.024 * i, 0.2 - 0.04 * i, -0.9);
  const auto frame =
      frame_of({strand_of(0, a, cam), strand_of(1, b, cam)}, Vector3d(0.3, 0.2, 1), cam);
  auto ramp = std::make_shared<v::ToonRamp>();
  ramp->width = 8;
  ramp->height = 1;
  const Eigen::Vector3f dark(0.2f, 0.1f, 0.4f), light(0.9f, 0.8f, 0.2f);
  for (int i = 0; i < 8; ++i) ramp->pixels.push_back(i < 6 ? dark : light);  // edge at x = 0.75
  v::HairStyle style = lit_style();
  style.shading.ramp = ramp;
  style.shading.centre_line = true;
  const Rendered r = render(frame, style);
  REQUIRE(r.curves.stats.outlines == 2);
  REQUIRE(r.curves.stats.band_edges >= 1);
  // The band edges: after the outlines and centre lines; one colour per side, the two bands.
  int checked = 0;
  for (size_t i = 2; i < r.curves.curves.size(); ++i) {
    const auto& c = r.curves.curves[i];
    if (c.left.front().color != dark) continue;  // a centre line
    for (const auto& s : c.left) CHECK(s.color == dark);
    for (const auto& s : c.right) CHECK(s.color == light);
    // Which wisp: the one whose outline holds most of it (they cross).
    int in1 = 0;
    for (int k = 0; k <= 20; ++k)
      in1 += inside_outline(r.wisps[1], wisp::diffusion::eval(c, k / 20.0), 0);
    int in0 = 0;
    for (int k = 0; k <= 20; ++k)
      in0 += inside_outline(r.wisps[0], wisp::diffusion::eval(c, k / 20.0), 0);
    const int w = in1 > in0 ? 1 : 0;
    for (int k = 0; k <= 200; ++k) {
      const double s = k / 200.0;
      const Vector2d p = wisp::diffusion::eval(c, s);
      CHECK(inside_outline(r.wisps[w], p, 0.15));
      bool active = false;
      for (const auto& iv : c.active) active |= s >= iv.first && s <= iv.second;
      // Active only where its wisp shows: for the back wisp, never inside the front one.
      if (w == 0 && active) CHECK(!inside_outline(r.wisps[1], p, -0.3));
    }
    // On the image, the edge is a sharp step: across it (1.5 px each side) the colours of the
    // two bands, where it is active and clear of other curves.
    ++checked;
  }
  CHECK(checked >= 1);
  // Both band colours appear inside the hair as flat areas.
  int dark_px = 0, light_px = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const Eigen::Vector3f c = r.at(x, y);
      dark_px += (c - dark).norm() < 0.02;
      light_px += (c - light).norm() < 0.02;
    }
  CHECK(dark_px > 50);
  CHECK(light_px > 50);
}

TEST_CASE("curves inside wisps without the arrangement's faces are an error, not dropped",
          "[vector][shading]") {
  const Camera cam;
  std::vector<Vector3d> a;
  for (int i = 0; i <= 10; ++i) a.emplace_back(-0.12 + 0.024 * i, 0.2 - 0.04 * i, -1.0);
  const auto frame = frame_of({strand_of(0, a, cam)}, Vector3d(0.3, 0.2, 1), cam);
  v::HairStyle inner = lit_style();
  inner.shading.centre_line = true;
  v::HairStyle outlines_only = lit_style();
  outlines_only.shading.centre_line = false;
  REQUIRE(v::needs_visible_regions(inner));
  REQUIRE(!v::needs_visible_regions(outlines_only));
  const std::vector<v::Wisp> wisps = v::build_wisps(frame, inner.geometry);
  v::ArrangementOptions o;
  o.view = v::image_rect(256, 256);
  const v::WispArrangement without = v::build_arrangement(wisps, o);
  CHECK_THROWS_AS(v::shade_hair(frame, wisps, without, inner), std::logic_error);
  CHECK(v::shade_hair(frame, wisps, without, outlines_only).curves.size() == 1);
  o.keep_faces = true;
  const v::WispArrangement with = v::build_arrangement(wisps, o);
  CHECK(v::shade_hair(frame, wisps, with, inner).stats.centre_lines == 1);
}

TEST_CASE("the highlight band sits at the analytic Kajiya-Kay peak, and only with specular on",
          "[vector][shading]") {
  const Camera cam;
  // An arc in the plane x = 0 (through the eye, so it projects to a vertical line), bulging
  // towards the camera: its tangent turns, and the specular peak is where T is perpendicular to H.
  const auto P = [](double phi) {
    return Vector3d(0, 0.3 * std::sin(phi), -1.3 + 0.3 * std::cos(phi));
  };
  std::vector<Vector3d> world;
  for (int i = 0; i <= 24; ++i) world.push_back(P(-1.0 + 2.0 * i / 24));
  const Vector3d L = Vector3d(0, 1, 0.6).normalized();
  const auto frame = frame_of({strand_of(0, world, cam)}, L, cam);
  // Analytic: T.H = 0 (H from the eye at the origin), by bisection on phi.
  const auto TdotH = [&](double phi) {
    const Vector3d T(0, std::cos(phi), -std::sin(phi));
    return T.dot((L + (-P(phi)).normalized()).normalized());
  };
  double lo = -1, hi = 1;
  REQUIRE(TdotH(lo) * TdotH(hi) < 0);
  for (int k = 0; k < 60; ++k)
    ((TdotH(lo) < 0) == (TdotH(0.5 * (lo + hi)) < 0) ? lo : hi) = 0.5 * (lo + hi);
  const Vector2d peak = cam.project(P(0.5 * (lo + hi)));

  v::HairStyle style = lit_style();
  style.specular.shape = v::HighlightShape::Band;
  style.specular.color = {0, 1, 0};  // a colour nothing else has
  style.specular.threshold = 0.6;
  style.specular.shininess = 60;
  const Rendered on = render(frame, style);
  CHECK(on.curves.stats.highlights == 1);
  Vector2d sum(0, 0);
  int count = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      if ((on.at(x, y) - style.specular.color).norm() < 0.1)
        sum += Vector2d(x + 0.5, y + 0.5), ++count;
  REQUIRE(count > 3);
  const Vector2d centre = sum / count;
  INFO("highlight centre " << centre.transpose() << " (" << count << " px), analytic peak "
                           << peak.transpose());
  CHECK((centre - peak).norm() <= 3.0);

  style.specular.shape = v::HighlightShape::None;
  const Rendered off = render(frame, style);
  CHECK(off.curves.stats.highlights == 0);
  int green = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) green += (off.at(x, y) - Eigen::Vector3f(0, 1, 0)).norm() < 0.3;
  CHECK(green == 0);
}

TEST_CASE("the anime band lies at H's elevation about the head's axis, closes at its ends",
          "[vector][shading][anime]") {
  wisp::sim::ProjectedFrame frame;
  frame.eye = Vector3d(0, 0, 2);
  frame.light_dir = Vector3d(0, 1, 1).normalized();
  frame.focal_px = 300;
  v::HighlightStyle style;
  style.band_width_deg = 10;
  style.band_extent_deg = 60;
  style.teeth = 2;
  style.tooth_depth = 1;
  const double deg = M_PI / 180;
  for (const Vector3d& up : {Vector3d(0, 1, 0), Vector3d(0.3, 1, 0).normalized()}) {
    frame.head_up = up;
    const v::AnimeBand band = v::anime_band(style, frame, Vector3d::Zero(), 0.1, 0.02);
    const Vector3d H = (frame.light_dir + Vector3d(0, 0, 1)).normalized();
    CHECK(band.latitude == Approx(std::asin(H.dot(up))).margin(1e-12));
    CHECK(band.period == Approx(0.2 / 2));
    // A head direction at latitude a and longitude b about the head's axis, b = 0 towards H.
    const auto at = [&](double a, double b) -> Vector3d {
      return 0.1 * (std::sin(a) * band.up +
                    std::cos(a) * (std::cos(b) * band.front + std::sin(b) * band.side));
    };
    const double lat = band.latitude, half = 5 * deg;
    // At H's longitude (a valley between teeth): exactly the band's width.
    CHECK(band.field(at(lat, 0)) == Approx(half));
    CHECK(band.field(at(lat + half - 1e-3, 0)) > 0);
    CHECK(band.field(at(lat + half + 1e-3, 0)) < 0);
    CHECK(band.field(at(lat - half + 1e-3, 0)) > 0);
    CHECK(band.field(at(lat - half - 1e-3, 0)) < 0);
    // Half a period away, a tooth reaches down a further band width (narrowed towards the end).
    const double b = 0.5 * band.period, narrow = std::sqrt(1 - std::pow(b / (60 * deg), 2));
    CHECK(band.field(at(lat - half * narrow * 2.9, b)) > 0);
    CHECK(band.field(at(lat - half * narrow * 3.1, b)) < 0);
    // Narrower towards its ends, closed beyond them, and nowhere on the far side.
    CHECK(band.field(at(lat, 50 * deg)) < band.field(at(lat, 20 * deg)));
    CHECK(band.field(at(lat, 61 * deg)) < 0);
    CHECK(band.field(at(lat, 180 * deg)) < 0);
  }
}

TEST_CASE("the anime band runs across neighbouring wisps as one crisp shape",
          "[vector][shading][anime]") {
  const Camera cam;
  // A head of radius 0.1 in front of the camera; strands run down its meridians from roots near
  // the crown, side by side and overlapping, the roots alternating in height so that their
  // order changes.
  const Vector3d c(0, 0, -0.5);
  const auto on_head = [&](double lat, double lon, double r) -> Vector3d {
    return c + r * Vector3d(std::cos(lat) * std::sin(lon), std::sin(lat),
                            std::cos(lat) * std::cos(lon));
  };
  std::vector<wisp::sim::ProjectedStrand> strands;
  for (int k = 0; k < 9; ++k) {
    const double lon = -0.6 + 1.2 * k / 8, top = k % 2 ? 0.9 : 1.3;
    std::vector<Vector3d> world;
    for (int i = 0; i <= 24; ++i) world.push_back(on_head(top - (top + 0.6) * i / 24, lon, 0.104));
    strands.push_back(strand_of(k, world, cam));
  }
  auto frame = frame_of(std::move(strands), Vector3d(0, 0.4, 1), cam);
  v::HairStyle style = lit_style();
  style.geometry.width = 0.03;
  style.specular.shape = v::HighlightShape::Anime;
  style.specular.color = {0, 1, 0};
  style.specular.max_width = 0.97;
  const Rendered r = render(frame, style);
  CHECK(r.curves.stats.highlights >= 5);
  // The highlight's pixels: one 8-connected shape (a flood fill from the first one finds them
  // all), so the pieces join across the wisps' edges without a shadow between them.
  std::vector<int> lit(256 * 256, 0);
  int total = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      if ((r.at(x, y) - style.specular.color).norm() < 0.15) lit[y * 256 + x] = 1, ++total;
  REQUIRE(total > 200);
  int first = 0;
  while (!lit[first]) ++first;
  std::vector<int> stack = {first};
  lit[first] = 2;
  int reached = 0;
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    ++reached;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = i % 256 + dx, y = i / 256 + dy;
        if (x < 0 || y < 0 || x >= 256 || y >= 256 || lit[y * 256 + x] != 1) continue;
        lit[y * 256 + x] = 2;
        stack.push_back(y * 256 + x);
      }
  }
  INFO(reached << " of " << total << " highlight pixels in the first shape");
  CHECK(reached >= 0.97 * total);
  // Its height is the band's: at the head's front, its width and its teeth, 8 + 8 degrees of
  // latitude on a radius of 0.1 at distance 0.5 seen with a focal length of 300 px: 17 px.
  int y0 = 256, y1 = 0;
  for (int i = 0; i < 256 * 256; ++i)
    if (lit[i] == 2) y0 = std::min(y0, i / 256), y1 = std::max(y1, i / 256);
  const double px = 16 * M_PI / 180 * 0.1 * 300 / 0.5;
  CHECK(y1 - y0 > 0.5 * px);
  CHECK(y1 - y0 < 1.5 * px);
}
