// Fur (data/scenes/fur.json): at five head angles the tufts cover at least 90 % of the length of
// the head's silhouette where fur grows (Sheppard's fins); no tuft goes from nothing to full
// opacity, or back, between consecutive frames (his alpha fins against popping); and a frame
// draws them in the PNG and as the SVG's "fur" group alike.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "diffusion/bezier.hpp"
#include "run_command.hpp"
#include "scene_fixture.hpp"

namespace render = wisp::render;
namespace sim = wisp::sim;
namespace vector = wisp::vector;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

const std::string kScene = WISP_SOURCE_DIR "/data/scenes/fur.json";
constexpr int kSize = 512;

const render::SceneFrames& frames() {
  return wisp::test::loaded_scene(kScene, kSize);
}

std::vector<int> five_angles() {
  return wisp::test::five_angles(frames().anim);
}

// The silhouette of the ellipsoid head x^T A x = 1 (A = diag(1/r^2)) seen from head-local eye e:
// where the normal A x is perpendicular to e - x, i.e. on the plane (A e).x = 1. In the unit
// sphere's coordinates y = x / r that is a circle: centre m / |m|^2, radius sqrt(1 - 1/|m|^2),
// m = e / r. Returns head-local points around it.
std::vector<Vector3d> rim(const Vector3d& radii, const Vector3d& eye_local, int samples) {
  const Vector3d m = eye_local.cwiseQuotient(radii);
  const Vector3d c = m / m.squaredNorm(), n = m.normalized();
  const double rho = std::sqrt(1 - 1 / m.squaredNorm());
  const Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  std::vector<Vector3d> out;
  for (int i = 0; i < samples; ++i) {
    const double a = 2 * M_PI * i / samples;
    out.push_back((c + rho * (std::cos(a) * u + std::sin(a) * w)).cwiseProduct(radii));
  }
  return out;
}

// A tuft's loops flattened to polygons.
std::vector<std::vector<Vector2d>> polygons(const vector::FurTuft& t) {
  std::vector<std::vector<Vector2d>> out;
  for (const auto& loop : t.loops) {
    wisp::diffusion::BezierPath path;
    path.points = loop;
    std::vector<Vector2d> poly;
    for (int i = 0; i < path.piece_count(); ++i)
      for (int j = 0; j < 8; ++j) poly.push_back(wisp::diffusion::eval(path.piece(i), j / 8.0));
    out.push_back(std::move(poly));
  }
  return out;
}

bool inside_or_near(const std::vector<Vector2d>& poly, const Vector2d& p, double near) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vector2d a = poly[j], b = poly[i];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
      in = !in;
    const Vector2d d = b - a;
    const double f = std::clamp((p - a).dot(d) / std::max(1e-12, d.squaredNorm()), 0.0, 1.0);
    if ((a + f * d - p).norm() <= near) return true;
  }
  return in;
}

// The share of the furred silhouette's length (pixels) that tufts of opacity >= 1/2 cover.
double silhouette_coverage(int k, const std::vector<vector::FurTuft>& tufts) {
  const render::SceneFrames& sf = frames();
  const sim::HeadPose& pose = sf.anim.frames[k].head;
  const sim::Camera camera = sim::Camera::look_at(sf.scene.camera);
  const std::vector<Vector3d> points = rim(sf.anim.head.radii, pose.to_local(camera.eye), 4096);
  std::vector<std::vector<std::vector<Vector2d>>> polys;
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const vector::FurTuft& t : tufts) {
    if (t.opacity < 0.5f) continue;
    polys.push_back(polygons(t));
    Eigen::AlignedBox2d box;
    for (const auto& p : polys.back())
      for (const Vector2d& q : p) box.extend(q);
    boxes.push_back(box);
  }
  double total = 0, covered = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vector3d& a = points[i];
    const Vector3d& b = points[(i + 1) % points.size()];
    if (!sim::in_fur_region(a.normalized(), sf.scene.fur) ||
        !sim::in_fur_region(b.normalized(), sf.scene.fur))
      continue;
    const Vector2d pa = camera.project(pose.to_world(a)), pb = camera.project(pose.to_world(b));
    const Vector2d mid = 0.5 * (pa + pb);
    const double len = (pb - pa).norm();
    total += len;
    bool hit = false;
    for (size_t t = 0; t < polys.size() && !hit; ++t) {
      if (boxes[t].exteriorDistance(mid) > 1) continue;
      for (const auto& poly : polys[t])
        if (inside_or_near(poly, mid, 1.0)) {
          hit = true;
          break;
        }
    }
    if (hit) covered += len;
  }
  return total > 0 ? covered / total : 0;
}

}  // namespace

TEST_CASE("fur tufts cover the silhouette where fur grows", "[apps][fur]") {
  for (int k : five_angles()) {
    const std::vector<vector::FurTuft> tufts = render::frame_fur(frames(), k);
    const double coverage = silhouette_coverage(k, tufts);
    INFO("frame " << k << ": " << tufts.size() << " tufts, coverage " << coverage);
    CHECK(tufts.size() >= 1000);
    CHECK(coverage >= 0.9);
    // Without the fins' fade band the silhouette is all but bare: the check can fail.
    render::SceneFrames narrow = frames();
    narrow.scene.style.fur.fin_band = 0.01;
    CHECK(silhouette_coverage(k, render::frame_fur(narrow, k)) < 0.9);
  }
}

TEST_CASE("fur tufts fade in and out over frames instead of popping", "[apps][fur]") {
  const render::SceneFrames& sf = frames();
  std::map<int, float> previous;
  double worst = 0;
  int appeared = 0;
  for (int k = 0; k < sf.frame_count(); ++k) {
    std::map<int, float> current;
    for (const vector::FurTuft& t : render::frame_fur(sf, k)) current[t.id] = t.opacity;
    if (k > 0) {
      for (const auto& [id, a] : current) {
        const auto it = previous.find(id);
        appeared += it == previous.end();
        worst = std::max(worst, double(a - (it == previous.end() ? 0.0f : it->second)));
      }
      for (const auto& [id, a] : previous) {
        const auto it = current.find(id);
        worst = std::max(worst, double(a - (it == current.end() ? 0.0f : it->second)));
      }
    }
    previous = std::move(current);
  }
  INFO("largest opacity change between frames " << worst << ", " << appeared << " tufts appeared");
  CHECK(appeared > 100);  // the head turns: tufts come and go
  CHECK(worst <= 0.5);
}

TEST_CASE("fur tufts are drawn in the PNG and as the SVG's fur group", "[apps][fur]") {
  const render::SceneFrames& sf = frames();
  const int k = five_angles()[2];
  render::FrameResult r = render::render_frame(
      sf.projected[k], render::frame_body(sf, k), render::frame_occluders(sf, k),
      render::frame_base(sf, k), render::frame_setup(sf.scene), nullptr);
  REQUIRE(r.picture.fur.size() >= 1000);
  const std::string svg = render::format_frame_svg(r.picture, render::SvgStyle::Embedded);
  const size_t group = svg.find("<g id=\"fur\"");
  REQUIRE(group != std::string::npos);
  size_t paths = 0;
  for (size_t at = svg.find("<path", group);
       at != std::string::npos && at < svg.find("</g>", group); at = svg.find("<path", at + 1))
    ++paths;
  CHECK(paths == r.picture.fur.size());
  // In the PNG the fur changes pixels just outside the base coat: the fuzz beyond the head.
  const std::vector<std::uint8_t> with = render::rasterize_frame(r.picture);
  r.picture.fur.clear();
  const std::vector<std::uint8_t> without = render::rasterize_frame(r.picture);
  size_t changed = 0;
  for (size_t i = 0; i < with.size(); i += 4) changed += with[i] != without[i];
  CHECK(changed > 2000);
  // Same input, same pixels.
  render::FrameResult again = render::render_frame(
      sf.projected[k], render::frame_body(sf, k), render::frame_occluders(sf, k),
      render::frame_base(sf, k), render::frame_setup(sf.scene), nullptr);
  CHECK(render::rasterize_frame(again.picture) == with);
}
