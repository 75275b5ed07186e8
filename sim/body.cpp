// BodyModel: see body.hpp. Ellipsoids and capsules share one tessellation, a UV sphere of
// `slices` x `stacks` around a local axis; a capsule is that sphere cut at the equator, its two
// halves moved to the ends of the axis and joined by a band of quads. Every vertex is scaled by
// the same factor k >= 1, the smallest that puts every face plane of the unit UV sphere at
// distance >= 1 from its centre: the polyhedron then contains the true surface (roots on the
// scalp project inside the drawn head) and exceeds it by at most r (k - 1), 0.4 % at 40 x 20.
#include "sim/body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

// A vertex of the sphere / capsule template: a point of the unit sphere (z is the axis, -z
// towards end 0) and where along the axis it hangs (0 = end 0, 1 = end 1).
struct TemplateVertex {
  Vector3d p;
  double along = 0;
};

struct Template {
  std::vector<TemplateVertex> vertices;
  std::vector<Eigen::Vector3i> triangles;
};

// `bands` > 0 makes a capsule: the equator ring is repeated bands + 1 times along the axis.
Template lathe(int slices, int stacks, int bands) {
  const bool capsule = bands > 0;
  Template t;
  const auto ring_point = [&](double theta, int j) {
    const double phi = 2 * M_PI * j / slices;
    return Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                    -std::cos(theta));
  };
  t.vertices.push_back({Vector3d(0, 0, -1), 0});  // pole of end 0
  std::vector<int> ring_start;
  const auto add_ring = [&](int i, double along) {
    ring_start.push_back(static_cast<int>(t.vertices.size()));
    const double theta = M_PI * i / stacks;
    for (int j = 0; j < slices; ++j) t.vertices.push_back({ring_point(theta, j), along});
  };
  for (int i = 1; i < stacks; ++i) {
    if (capsule && 2 * i == stacks) {
      for (int b = 0; b <= bands; ++b) add_ring(i, double(b) / bands);
    } else {
      add_ring(i, capsule && 2 * i > stacks ? 1.0 : 0.0);
    }
  }
  const int pole1 = static_cast<int>(t.vertices.size());
  t.vertices.push_back({Vector3d(0, 0, 1), capsule ? 1.0 : 0.0});

  const auto at = [&](int ring, int j) { return ring_start[ring] + (j % slices); };
  const int rings = static_cast<int>(ring_start.size());
  for (int j = 0; j < slices; ++j) {
    t.triangles.emplace_back(0, at(0, j), at(0, j + 1));
    for (int r = 0; r + 1 < rings; ++r) {
      t.triangles.emplace_back(at(r, j), at(r + 1, j), at(r + 1, j + 1));
      t.triangles.emplace_back(at(r, j), at(r + 1, j + 1), at(r, j + 1));
    }
    t.triangles.emplace_back(pole1, at(rings - 1, j + 1), at(rings - 1, j));
  }
  // Orient every triangle outwards: away from the nearest point of the axis (a capsule of
  // radius 1 and axis length 2 for this check).
  for (auto& tri : t.triangles) {
    Vector3d v[3];
    for (int k = 0; k < 3; ++k) {
      const TemplateVertex& tv = t.vertices[tri[k]];
      v[k] = tv.p + Vector3d(0, 0, 2.0 * tv.along);
    }
    const Vector3d c = (v[0] + v[1] + v[2]) / 3;
    const Vector3d inside(0, 0, std::clamp(c.z(), 0.0, capsule ? 2.0 : 0.0));
    if ((v[1] - v[0]).cross(v[2] - v[0]).dot(c - inside) < 0) std::swap(tri[1], tri[2]);
  }
  return t;
}

// The circumscribing factor of the unit UV sphere: 1 / (smallest face-plane distance).
double circumscribe_factor(const Template& sphere) {
  double nearest = 1;
  for (const auto& tri : sphere.triangles) {
    const Vector3d& a = sphere.vertices[tri[0]].p;
    const Vector3d n = (sphere.vertices[tri[1]].p - a).cross(sphere.vertices[tri[2]].p - a);
    if (n.norm() < 1e-15) continue;
    nearest = std::min(nearest, std::abs(n.normalized().dot(a)));
  }
  return 1 / nearest;
}

// An orthonormal right-handed frame (u, v, w) with w along `axis`.
void axis_frame(const Vector3d& axis, Vector3d& u, Vector3d& v, Vector3d& w) {
  w = axis.norm() > 1e-12 ? Vector3d(axis.normalized()) : Vector3d(0, -1, 0);
  // The seam of the lathe faces +y-ish when possible: pick the helper least aligned with w.
  const Vector3d helper = std::abs(w.z()) < 0.9 ? Vector3d::UnitZ() : Vector3d::UnitX();
  u = helper.cross(w).normalized();
  v = w.cross(u);
}

// Appends the capsule template placed between ends a and b with radius r.
void place_capsule(const Template& t, double k, const Vector3d& a, const Vector3d& b, double r,
                   TriangleMesh& out) {
  Vector3d u, v, w;
  axis_frame(b - a, u, v, w);
  const int base = static_cast<int>(out.vertices.size());
  for (const TemplateVertex& tv : t.vertices) {
    const Vector3d q = k * r * tv.p;
    out.vertices.push_back(a + tv.along * (b - a) + q.x() * u + q.y() * v + q.z() * w);
  }
  for (const auto& tri : t.triangles)
    out.triangles.push_back(tri + Eigen::Vector3i::Constant(base));
}

// Appends the sphere template as an ellipsoid: the template axis z becomes y (poles at the crown
// and under the chin), then the radii scale it.
void place_ellipsoid(const Template& t, double k, const Vector3d& center, const Vector3d& radii,
                     TriangleMesh& out) {
  const int base = static_cast<int>(out.vertices.size());
  for (const TemplateVertex& tv : t.vertices) {
    // (x, y, z) -> (x, -z, y) is a rotation (det +1): orientation is kept.
    const Vector3d p(tv.p.x(), -tv.p.z(), tv.p.y());
    out.vertices.push_back(center + k * radii.cwiseProduct(p));
  }
  for (const auto& tri : t.triangles)
    out.triangles.push_back(tri + Eigen::Vector3i::Constant(base));
}

// x^p for x >= 0, with the common exponents of the chest (and their halves) done by products.
double power(double x, double p) {
  if (p == 1) return x;
  if (p == 2) return x * x;
  if (p == 3) return x * x * x;
  if (p == 4) return (x * x) * (x * x);
  if (p == 0) return 1;
  return std::pow(x, p);
}

// Beyond this distance (m) from the chest's bounding box, body_distance returns that distance.
constexpr double kFar = 0.05;

// ((x/a)^2 + (z/c)^2)^(e/2) + |y/b|^e: below 1 inside the superellipsoid with radii (a, b, c).
double superellipsoid_value(const Vector3d& p, const Vector3d& radii, double e) {
  const Vector3d q = p.cwiseQuotient(radii);
  return power(q.x() * q.x() + q.z() * q.z(), 0.5 * e) + power(std::abs(q.y()), e);
}

// Appends the sphere template as a superellipsoid around y (see body.hpp): each point of the
// unit sphere keeps its direction around the axis, its radius rho and height h becoming
// rho^(2/e) and sign(h) |h|^(2/e), so that rho^e + |h|^e = 1. Not circumscribed: the chest
// collides with nothing.
void place_superellipsoid(const Template& t, const Vector3d& center, const Vector3d& radii,
                          double e, TriangleMesh& out) {
  const int base = static_cast<int>(out.vertices.size());
  for (const TemplateVertex& tv : t.vertices) {
    const Vector3d p(tv.p.x(), -tv.p.z(), tv.p.y());
    const double rho = std::hypot(p.x(), p.z());
    const double new_rho = std::pow(rho, 2 / e);
    const double h = std::copysign(std::pow(std::abs(p.y()), 2 / e), p.y());
    const double scale = rho > 1e-12 ? new_rho / rho : 0.0;
    out.vertices.push_back(center + radii.cwiseProduct(Vector3d(p.x() * scale, h, p.z() * scale)));
  }
  for (const auto& tri : t.triangles)
    out.triangles.push_back(tri + Eigen::Vector3i::Constant(base));
}

// Ericson's closest points of two segments (Real-Time Collision Detection, 5.1.9): the squared
// distance between p1q1 and p2q2.
double segment_distance2(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2,
                         const Vector3d& q2) {
  const Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 1e-18 && e <= 1e-18) return r.squaredNorm();
  if (a <= 1e-18) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 1e-18) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 1e-18 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p1 + d1 * s - (p2 + d2 * t)).squaredNorm();
}

}  // namespace

BodyParams body_params(const HeadParams& head) {
  BodyParams b;
  const Vector3d& r = head.radii;
  if (head.shape == HeadKind::Ellipsoid) {
    b.neck_top = Vector3d(0, -0.43 * r.y(), -0.13 * r.z());
    b.neck_radius = 0.65 * r.x();
  }
  b.shoulders = Capsule{head.shoulder_center, head.shoulder_half_width, head.shoulder_radius};
  // The neck ends at the top of the shoulder capsule's core, a little behind its axis; the chest
  // hangs from the capsule and is a little wider than it.
  b.neck_bottom = head.shoulder_center + Vector3d(0, 0.015, -0.01);
  b.chest_center = head.shoulder_center + Vector3d(0, -0.22, 0.0);
  b.chest_radii = Vector3d(head.shoulder_half_width + 0.04, 0.28, head.shoulder_radius + 0.025);
  return b;
}

void validate(const BodyParams& b) {
  require(b.slices >= 3 && b.slices <= 1024, "slices", "must be in [3, 1024]");
  require(b.stacks >= 2 && b.stacks <= 1024, "stacks", "must be in [2, 1024]");
  require(b.neck_top.allFinite(), "neck_top", "not finite");
  require(b.neck_bottom.allFinite(), "neck_bottom", "not finite");
  require(b.shoulders.center.allFinite(), "shoulder_center", "not finite");
  require(b.chest_center.allFinite(), "chest_center", "not finite");
  require(b.neck_radius > 0 && std::isfinite(b.neck_radius), "neck_radius", "must be > 0");
  require(b.shoulders.radius > 0 && std::isfinite(b.shoulders.radius), "shoulder_radius",
          "must be > 0");
  require(b.shoulders.half_width >= 0 && std::isfinite(b.shoulders.half_width),
          "shoulder_half_width", "must be >= 0");
  require(b.chest_radii.minCoeff() > 0 && b.chest_radii.allFinite(), "chest_radii",
          "every radius must be > 0");
  require(b.chest_exponent >= 1 && b.chest_exponent <= 16, "chest_exponent", "must be in [1, 16]");
}

BodyModel::BodyModel(const HeadGeometry& head, const BodyParams& body)
    : body_((validate_part(body, "body"), body)), shape_(head) {
  const Template sphere = lathe(body_.slices, body_.stacks, 0);
  const double k = circumscribe_factor(sphere);
  const int capsule_stacks = body_.stacks + body_.stacks % 2;
  const double kc = circumscribe_factor(lathe(body_.slices, capsule_stacks, 0));
  // Cylinder bands about as long as the cap's quads are tall, so that depth sorting works on
  // triangles of similar size everywhere.
  const auto bands = [&](double length, double radius) {
    return std::clamp(static_cast<int>(std::ceil(length / (M_PI * radius / capsule_stacks))), 1,
                      256);
  };

  if (body_.head) {
    if (head.shape == HeadKind::Ellipsoid)
      place_ellipsoid(sphere, k, Vector3d::Zero(), head.radii, head_);
    else
      head_ = head.mesh;
  }
  if (body_.torso) {
    const Capsule& s = body_.shoulders;
    const Vector3d half(s.half_width, 0, 0);
    const Template capsule = lathe(body_.slices, capsule_stacks, bands(2 * s.half_width, s.radius));
    place_capsule(capsule, kc, s.center - half, s.center + half, s.radius, torso_);
    const std::size_t before = torso_.triangles.size();
    place_superellipsoid(sphere, body_.chest_center, body_.chest_radii, body_.chest_exponent,
                         torso_);
    chest_triangles_ = torso_.triangles.size() - before;
  }
  if (body_.neck) {
    const double length =
        (body_.neck_top - body_.neck_bottom).norm();  // at rest (the head's pose moves the top)
    const Template capsule = lathe(body_.slices, capsule_stacks, bands(length, body_.neck_radius));
    for (const TemplateVertex& tv : capsule.vertices) {
      neck_offset_.push_back(kc * tv.p);
      neck_along_.push_back(tv.along);
    }
    neck_triangles_ = capsule.triangles;
  }
}

std::vector<Eigen::Matrix3d> BodyModel::world_triangles(
    const HeadPose& pose, std::vector<int>* part, std::vector<Eigen::Matrix3d>* normals) const {
  std::vector<Eigen::Matrix3d> out;
  if (part) part->clear();
  if (normals) normals->clear();
  std::vector<Vector3d> vertex_normal;
  const auto add = [&](const std::vector<Vector3d>& v, const std::vector<Eigen::Vector3i>& tris,
                       int which) {
    if (normals) {
      // Area-weighted mean of the face normals around each vertex.
      vertex_normal.assign(v.size(), Vector3d::Zero());
      for (const auto& t : tris) {
        const Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
        for (int k = 0; k < 3; ++k) vertex_normal[t[k]] += n;
      }
      for (Vector3d& n : vertex_normal)
        if (n.norm() > 1e-300) n.normalize();
    }
    for (const auto& t : tris) {
      Eigen::Matrix3d tri;
      tri << v[t[0]], v[t[1]], v[t[2]];
      out.push_back(tri);
      if (part) part->push_back(which);
      if (normals) {
        tri << vertex_normal[t[0]], vertex_normal[t[1]], vertex_normal[t[2]];
        normals->push_back(tri);
      }
    }
  };
  out.reserve(torso_.triangles.size() + neck_triangles_.size() + head_.triangles.size());
  std::vector<Vector3d> world;
  // Painter's ties are broken by this order: torso, neck, head.
  world.resize(torso_.vertices.size());
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = torso_.vertices[i] + pose.position;
  add(world, torso_.triangles, kBodyTorso);
  if (!neck_along_.empty()) {
    const Vector3d top = pose.to_world(body_.neck_top);
    const Vector3d bottom = pose.position + body_.neck_bottom;
    Vector3d u, v, w;
    axis_frame(bottom - top, u, v, w);
    const double r = body_.neck_radius;
    world.resize(neck_offset_.size());
    for (std::size_t i = 0; i < world.size(); ++i) {
      const Vector3d& q = neck_offset_[i];
      world[i] = top + neck_along_[i] * (bottom - top) + r * (q.x() * u + q.y() * v + q.z() * w);
    }
    add(world, neck_triangles_, kBodyNeck);
  }
  world.resize(head_.vertices.size());
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = pose.to_world(head_.vertices[i]);
  add(world, head_.triangles, kBodyHead);
  return out;
}

bool BodyModel::inside_other(const HeadPose& pose, const Vector3d& x, int solid) const {
  if (solid != 0 && body_.head && shape_.distance(pose.to_local(x)) < 0) return true;
  if (solid != 1 && body_.neck) {
    const double r = body_.neck_radius;
    if (segment_distance2(x, x, pose.to_world(body_.neck_top), pose.position + body_.neck_bottom) <
        r * r)
      return true;
  }
  if (!body_.torso) return false;
  const Vector3d b = x - pose.position;  // body frame
  if (solid != 2 && body_.shoulders.distance(b, nullptr) < 0) return true;
  if (solid != 3 &&
      superellipsoid_value(b - body_.chest_center, body_.chest_radii, body_.chest_exponent) < 1)
    return true;
  return false;
}

ProjectedBody BodyModel::project(const HeadPose& pose, const Camera& camera,
                                 const Vector3d& light_dir) const {
  const Vector3d light =
      light_dir.norm() > 1e-12 ? Vector3d(light_dir.normalized()) : Vector3d::Zero();
  std::vector<int> part;
  std::vector<Eigen::Matrix3d> normals;
  const std::vector<Eigen::Matrix3d> tris = world_triangles(pose, &part, &normals);
  // world_triangles lists the shoulders, the chest, the neck, then the head.
  const std::size_t shoulders_end = body_.torso ? torso_.triangles.size() - chest_triangles_ : 0;
  const auto solid_of = [&](std::size_t i) {
    return part[i] == kBodyHead ? 0 : part[i] == kBodyNeck ? 1 : i < shoulders_end ? 2 : 3;
  };
  ProjectedBody out;
  out.triangles.reserve(tris.size() / 2 + 1);
  constexpr double kNear = 1e-3;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const Eigen::Matrix3d& t = tris[i];
    const Vector3d a = t.col(0), b = t.col(1), c = t.col(2);
    if ((a - camera.eye).dot(camera.forward) < kNear ||
        (b - camera.eye).dot(camera.forward) < kNear ||
        (c - camera.eye).dot(camera.forward) < kNear)
      continue;
    const Vector3d n = (b - a).cross(c - a);
    if (!(n.dot(a - camera.eye) < 0)) continue;  // back-facing, edge-on or degenerate
    const int solid = solid_of(i);
    if (inside_other(pose, a, solid) && inside_other(pose, b, solid) &&
        inside_other(pose, c, solid))
      continue;
    BodyTriangle bt;
    for (int k = 0; k < 3; ++k) bt.p[k] = camera.project(t.col(k));
    bt.depth = ((a + b + c) / 3 - camera.eye).norm();
    const auto half_lambert = [&](const Vector3d& normal) {
      return static_cast<float>(std::clamp(0.5 * (1 + normal.dot(light)), 0.0, 1.0));
    };
    bt.shade = half_lambert(n.normalized());
    for (int k = 0; k < 3; ++k) bt.vertex_shade[k] = half_lambert(normals[i].col(k));
    bt.part = part[i];
    out.triangles.push_back(bt);
  }
  // Back to front; equal depths keep the build order (stable), so the result is deterministic.
  std::stable_sort(out.triangles.begin(), out.triangles.end(),
                   [](const BodyTriangle& x, const BodyTriangle& y) { return x.depth > y.depth; });
  return out;
}

ProjectedBody project_body(const HeadPose& pose, const HeadGeometry& head, const BodyParams& body,
                           const CameraParams& camera, const Vector3d& light_dir) {
  return BodyModel(head, body).project(pose, Camera::look_at(camera), light_dir);
}

double body_distance(const BodyParams& body, const HeadPose& pose, const Vector3d& x,
                     Vector3d* normal) {
  double best = std::numeric_limits<double>::infinity();
  Vector3d n = Vector3d::UnitY();
  if (body.neck) {
    const Vector3d a = pose.to_world(body.neck_top), b = pose.position + body.neck_bottom;
    const Vector3d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 1e-30 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const Vector3d off = x - (a + s * ab);
    const double len = off.norm();
    best = len - body.neck_radius;
    n = len > 1e-12 ? Vector3d(off / len) : Vector3d::UnitY();
  }
  if (body.torso) {
    const double e = body.chest_exponent;
    const Vector3d& r = body.chest_radii;
    const Vector3d b = x - pose.position - body.chest_center;
    // Far from the chest, the distance to its bounding box is a cheap lower bound: callers only
    // need the distance when it is small.
    const double box = (b.cwiseAbs() - r).cwiseMax(0.0).norm();
    if (box > kFar) {
      if (box < best) {
        best = box;
        n = (b.cwiseAbs() - r).cwiseMax(0.0).cwiseProduct(b.cwiseSign()).normalized();
      }
    } else {
      const Vector3d q = b.cwiseQuotient(r);
      const double rho2 = q.x() * q.x() + q.z() * q.z(), ay = std::abs(q.y());
      const double g = power(rho2, 0.5 * e) + power(ay, e);
      // grad_q of g, then of F = g^(1/e) with respect to the world point (divide by the radii).
      const double radial = rho2 > 1e-300 ? e * power(rho2, 0.5 * e - 1) : 0.0;
      const Vector3d dg(radial * q.x(), ay > 0 ? e * power(ay, e - 1) * (q.y() > 0 ? 1 : -1) : 0,
                        radial * q.z());
      double d = -r.minCoeff();
      Vector3d nc = Vector3d::UnitY();
      if (g > 1e-300) {
        const double f = std::pow(g, 1 / e);
        const Vector3d grad = (f / (e * g)) * dg.cwiseQuotient(r);
        const double gn = grad.norm();
        if (gn > 1e-12) {
          d = (f - 1) / gn;
          nc = grad / gn;
        }
      }
      if (d < best) {
        best = d;
        n = nc;
      }
    }
  }
  if (normal) *normal = n;
  return best;
}

bool body_blocks(const BodyParams& body, const HeadPose& pose, const Vector3d& eye,
                 const Vector3d& x, double shrink, double ignore) {
  const Vector3d d = x - eye;
  const double len = d.norm();
  if (len <= ignore) return false;
  const Vector3d end = eye + d * ((len - ignore) / len);
  const auto capsule = [&](const Vector3d& a, const Vector3d& b, double r) {
    const double rr = std::max(r - shrink, 1e-6);
    return segment_distance2(eye, end, a, b) < rr * rr;
  };
  if (body.neck &&
      capsule(pose.to_world(body.neck_top), pose.position + body.neck_bottom, body.neck_radius))
    return true;
  if (!body.torso) return false;
  const Capsule& s = body.shoulders;
  const Vector3d c = pose.position + s.center, half(s.half_width, 0, 0);
  if (capsule(c - half, c + half, s.radius)) return true;
  const Vector3d radii = (body.chest_radii - Vector3d::Constant(shrink)).cwiseMax(1e-6);
  const Vector3d centre = pose.position + body.chest_center;
  // The superellipsoid's inside function is convex, hence unimodal along the segment: a golden
  // section search finds its minimum (to 1e-9 of the segment, far below a millimetre).
  const auto value = [&](double f) {
    return superellipsoid_value(eye + f * (end - eye) - centre, radii, body.chest_exponent);
  };
  double lo = 0, hi = 1;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = value(x1), f2 = value(x2);
  for (int it = 0; it < 44 && f1 >= 1 && f2 >= 1; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = value(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = value(x2);
    }
  }
  return std::min({f1, f2, value(0), value(1)}) < 1;
}

}  // namespace wisp::sim
