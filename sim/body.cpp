// BodyShape and BodyModel: see body.hpp. The head is a UV sphere of `slices` x `stacks` scaled to
// the ellipsoid, every vertex pushed out by the same factor k >= 1, the smallest that puts every
// face plane of the unit UV sphere at distance >= 1 from its centre: the polyhedron then contains
// the true surface (roots on the scalp project inside the drawn head) and exceeds it by at most
// r (k - 1), 0.05 % at 96 x 48. The sweeps' vertices lie on their true surfaces.
#include "sim/body.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

// Head-local to world.
Eigen::Isometry3d head_frame(const HeadPose& pose) {
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.linear() = pose.rotation.toRotationMatrix();
  frame.translation() = pose.position;
  return frame;
}

// A UV sphere of unit radius around the y axis (poles at the crown and under the chin), outward
// counter-clockwise triangles.
TriangleMesh uv_sphere(int slices, int stacks) {
  TriangleMesh m;
  m.vertices.push_back(Vector3d(0, -1, 0));
  for (int i = 1; i < stacks; ++i) {
    const double theta = M_PI * i / stacks;
    for (int j = 0; j < slices; ++j) {
      const double phi = 2 * M_PI * j / slices;
      m.vertices.push_back(Vector3d(std::sin(theta) * std::cos(phi), -std::cos(theta),
                                    std::sin(theta) * std::sin(phi)));
    }
  }
  m.vertices.push_back(Vector3d(0, 1, 0));
  // Rings go up (+y) and around from +x towards +z: (up, around) is outward, as for sweeps.
  m.triangles = pole_to_pole_triangles(slices, stacks);
  return m;
}

// The circumscribing factor of a unit-sphere mesh: 1 / (smallest face-plane distance).
double circumscribe_factor(const TriangleMesh& sphere) {
  double nearest = 1;
  for (const auto& tri : sphere.triangles) {
    const Vector3d& a = sphere.vertices[tri[0]];
    const Vector3d n = (sphere.vertices[tri[1]] - a).cross(sphere.vertices[tri[2]] - a);
    if (n.norm() < 1e-15) continue;
    nearest = std::min(nearest, std::abs(n.normalized().dot(a)));
  }
  return 1 / nearest;
}

// The rotation whose y axis runs from `bottom` to `top` and whose z axis is as close to
// `forward` as that allows, placed at `bottom`.
Eigen::Isometry3d axis_frame(const Vector3d& bottom, const Vector3d& top, const Vector3d& forward) {
  const Vector3d y = (top - bottom).normalized();
  Vector3d z = forward - forward.dot(y) * y;
  if (z.norm() < 1e-9) z = y.unitOrthogonal();
  z.normalize();
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.linear().col(0) = y.cross(z);
  f.linear().col(1) = y;
  f.linear().col(2) = z;
  f.translation() = bottom;
  return f;
}

Vector3d mirror_x(const Vector3d& v) {
  return Vector3d(-v.x(), v.y(), v.z());
}

// Outward normals of a mesh: area-weighted means of the face normals around each vertex.
std::vector<Vector3d> mesh_normals(const TriangleMesh& m) {
  std::vector<Vector3d> n(m.vertices.size(), Vector3d::Zero());
  for (const auto& t : m.triangles) {
    const Vector3d f =
        (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    for (int k = 0; k < 3; ++k) n[t[k]] += f;
  }
  for (Vector3d& v : n)
    if (v.norm() > 1e-300) v.normalize();
  return n;
}

// A profile from samples (height, half-width, half-depth, centre offset) over [h0, h1]: t is
// the height's fraction of the way, x and z values scaled.
Sweep profile(std::initializer_list<std::array<double, 4>> rows, double h0, double h1, double sx,
              double sz) {
  Sweep s;
  for (const auto& r : rows) {
    s.t.push_back((r[0] - h0) / (h1 - h0));
    s.half_width.push_back(sx * r[1]);
    s.half_depth.push_back(sz * r[2]);
    s.offset.push_back(sz * r[3]);
  }
  s.t.front() = 0;
  s.t.back() = 1;
  return s;
}

// Nearest distance between a point and a segment's points (for bounding-sphere rejection).
double segment_point_distance(const Vector3d& a, const Vector3d& b, const Vector3d& p) {
  const Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 1e-30 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

// Sphere tracing from `eye` towards `x` against a signed distance: is a surface met before
// `limit` (distance from the eye)?
template <class Distance>
bool trace(const Vector3d& eye, const Vector3d& dir, double limit, const Distance& distance) {
  double s = 0;
  for (int it = 0; it < 400 && s < limit; ++it) {
    const double d = distance(eye + s * dir);
    if (d < 1e-5) return true;
    // The estimates are first order: step a little short of them.
    s += std::max(0.9 * d, 1e-4);
  }
  return false;
}

}  // namespace

BodyParams body_params(const HeadParams& head) {
  BodyParams b;
  const Vector3d& s = head.shoulder_center;
  const double sx = head.shoulder_half_width / 0.16, sz = head.shoulder_radius / 0.07;
  // Heights h above the acromions (the outer ends of the shoulder line, where the trapezius
  // slope meets the deltoid), 6 cm above shoulder_center (the old shoulder capsule's axis, whose
  // top the hair rested on). The torso: waist, chest, armpits, the shoulders' round, then the
  // trapezius slope up into the neck's base, closing inside the neck.
  const double acromion = s.y() + 0.06;
  const double h0 = -0.58, h1 = 0.09;
  b.torso_shape = profile({{h0, 0, 0, 0},
                           {-0.52, 0.115, 0.085, 0.0},
                           {-0.40, 0.125, 0.095, 0.012},
                           {-0.26, 0.138, 0.100, 0.02},
                           {-0.14, 0.150, 0.095, 0.018},
                           {-0.07, 0.152, 0.085, 0.01},
                           {-0.02, 0.150, 0.072, 0.0},
                           {0.0, 0.144, 0.066, -0.005},
                           {0.02, 0.124, 0.060, -0.012},
                           {0.04, 0.085, 0.054, -0.018},
                           {0.055, 0.058, 0.048, -0.02},
                           {0.07, 0.042, 0.040, -0.02},
                           {h1, 0, 0, -0.02}},
                          h0, h1, sx, sz);
  b.torso_bottom = Vector3d(0, acromion + h0, s.z());
  b.torso_length = h1 - h0;
  // The +x arm, hanging: from below the elbow (the forearm leaves the picture with the torso),
  // a little out and back, up to the deltoid's dome under the acromion; its inner half stays
  // inside the torso's shoulder.
  b.arm_bottom = Vector3d(sx * 0.2, acromion - 0.56, s.z() - 0.03);
  b.shoulder = Vector3d(sx * 0.17, acromion + 0.004, s.z() - 0.008);
  // Elbow at 0.45, biceps, deltoid, and a dome 3 cm high.
  b.arm_shape = profile({{0, 0, 0, 0},
                         {0.04, 0.031, 0.033, 0},
                         {0.45, 0.035, 0.038, 0},
                         {0.68, 0.041, 0.044, 0},
                         {0.946, 0.047, 0.049, 0},
                         {1, 0, 0, 0}},
                        0, 1, sz, sz);
  // The neck: from inside the torso, flaring where it leaves the trapezius, up into the head.
  const Vector3d& r = head.radii;
  double neck = 0.051;
  if (head.shape == HeadKind::Ellipsoid) {
    b.neck_top = Vector3d(0, -0.43 * r.y(), -0.13 * r.z());
    neck = 0.65 * r.x();
  }
  b.neck_bottom = Vector3d(0, acromion, s.z() - 0.015);
  b.neck_shape = profile({{0, 0, 0, 0},
                          {0.1, 1.1, 1.1, 0},
                          {0.4, 1.07, 1.07, 0},
                          {0.6, 1.02, 1.02, 0},
                          {0.75, 1.0, 1.0, 0},
                          {0.9, 1.0, 1.0, 0},
                          {1, 0, 0, 0}},
                         0, 1, neck, neck);
  b.torso_turn = head.torso_turn;
  return b;
}

void validate(const BodyParams& b) {
  const auto fail = [](const char* field, const std::string& what) {
    throw std::invalid_argument(std::string(field) + ": " + what);
  };
  if (b.slices < 3 || b.slices > 1024) fail("slices", "must be in [3, 1024]");
  if (b.stacks < 2 || b.stacks > 1024) fail("stacks", "must be in [2, 1024]");
  if (!(b.torso_turn >= 0 && b.torso_turn <= 1)) fail("torso_turn", "must be in [0, 1]");
  validate_sweep(b.torso_shape, "torso_shape");
  validate_sweep(b.arm_shape, "arm_shape");
  validate_sweep(b.neck_shape, "neck_shape");
  const std::pair<const Vector3d*, const char*> points[] = {{&b.torso_bottom, "torso_bottom"},
                                                            {&b.arm_bottom, "arm_bottom"},
                                                            {&b.shoulder, "shoulder"},
                                                            {&b.neck_bottom, "neck_bottom"},
                                                            {&b.neck_top, "neck_top"}};
  for (const auto& [p, field] : points)
    if (!p->allFinite()) fail(field, "not finite");
  if (!(b.torso_length > 0) || !std::isfinite(b.torso_length)) fail("torso_length", "must be > 0");
  if (!((b.shoulder - b.arm_bottom).norm() > 1e-3))
    fail("shoulder", "must be away from arm_bottom");
}

double head_yaw(const HeadPose& pose) {
  const Vector3d f = pose.rotation * Vector3d::UnitZ();
  return std::hypot(f.x(), f.z()) > 1e-9 ? std::atan2(f.x(), f.z()) : 0.0;
}

Eigen::Isometry3d body_frame(const HeadPose& pose, double torso_turn) {
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.linear() = Eigen::AngleAxisd(torso_turn * head_yaw(pose), Vector3d::UnitY()).toRotationMatrix();
  f.translation() = pose.position;
  return f;
}

BodyShape::BodyShape(const BodyParams& body)
    : body_((validate_part(body, "body"), body)),
      neck_(body.neck_shape),
      torso_(body.torso_shape),
      arm_(body.arm_shape) {}

const SweepShape& BodyShape::shape(int solid) const {
  return solid == kNeck ? neck_ : solid == kTorso ? torso_ : arm_;
}

BodyShape::Placement BodyShape::placement(const HeadPose& pose, int solid) const {
  const Eigen::Isometry3d body = body_frame(pose, body_.torso_turn);
  const Vector3d forward = body.linear().col(2);
  Placement p;
  switch (solid) {
    case kNeck: {
      const Vector3d bottom = body * body_.neck_bottom, top = pose.to_world(body_.neck_top);
      p.frame = axis_frame(bottom, top, forward);
      p.length = (top - bottom).norm();
      break;
    }
    case kTorso:
      p.frame = body * Eigen::Translation3d(body_.torso_bottom);
      p.length = body_.torso_length;
      break;
    default: {
      const bool plus = solid == kArmPlus;
      const Vector3d bottom = plus ? body_.arm_bottom : mirror_x(body_.arm_bottom);
      const Vector3d shoulder = plus ? body_.shoulder : mirror_x(body_.shoulder);
      p.frame = axis_frame(body * bottom, body * shoulder, forward);
      p.length = (shoulder - bottom).norm();
    }
  }
  return p;
}

BodyShape::Posed BodyShape::posed(const HeadPose& pose) const {
  Posed p;
  for (int s = 0; s < kSolids; ++s) {
    p.at[s] = placement(pose, s);
    p.to_local[s] = p.at[s].frame.inverse();
  }
  return p;
}

double BodyShape::solid_distance(int solid, const Posed& at, const Vector3d& x,
                                 Vector3d* normal) const {
  Vector3d n;
  const double d =
      shape(solid).distance(at.to_local[solid] * x, at.at[solid].length, normal ? &n : nullptr);
  if (normal) *normal = at.at[solid].frame.linear() * n;
  return d;
}

double BodyShape::distance(const Posed& at, const Vector3d& x, Vector3d* normal) const {
  double best = std::numeric_limits<double>::infinity();
  int nearest = -1;
  for (int solid = 0; solid < kSolids; ++solid) {
    if (!drawn(solid)) continue;
    const double d = solid_distance(solid, at, x);
    if (d < best) {
      best = d;
      nearest = solid;
    }
  }
  if (normal && nearest >= 0) solid_distance(nearest, at, x, normal);  // only its normal
  return best;
}

bool BodyShape::blocks(const Posed& at, const Vector3d& eye, const Vector3d& x, double shrink,
                       double ignore) const {
  const double len = (x - eye).norm();
  if (len <= ignore) return false;
  const Vector3d dir = (x - eye) / len;
  const Vector3d end = eye + (len - ignore) * dir;
  for (int solid = 0; solid < kSolids; ++solid) {
    if (!drawn(solid)) continue;
    const Placement& p = at.at[solid];
    const Vector3d centre = p.frame * Vector3d(0, 0.5 * p.length, 0);
    if (segment_point_distance(eye, end, centre) > 0.5 * p.length + shape(solid).max_radius())
      continue;
    if (trace(eye, dir, len - ignore,
              [&](const Vector3d& q) { return solid_distance(solid, at, q) + shrink; }))
      return true;
  }
  return false;
}

BodyModel::BodyModel(const HeadGeometry& head, const BodyParams& body)
    : shape_(body), head_shape_(head) {
  const BodyParams& b = shape_.params();
  if (b.head && b.face) face_ = face_lines(head_shape_);
  if (b.head) {
    if (head.shape == HeadKind::Ellipsoid) {
      const TriangleMesh sphere = uv_sphere(b.slices, b.stacks);
      const double k = circumscribe_factor(sphere);
      for (const Vector3d& p : sphere.vertices) {
        head_.vertices.push_back(k * head.radii.cwiseProduct(p));
        head_.normals.push_back(p.cwiseQuotient(head.radii).normalized());
      }
      head_.triangles = sphere.triangles;
    } else {
      head_.vertices = head.mesh.vertices;
      head_.triangles = head.mesh.triangles;
      head_.normals = mesh_normals(head.mesh);
    }
  }
  // Sweeps get rings about as far apart as their vertices around: triangles of similar shape.
  const auto build = [&](int solid, double length, int slices) {
    const SweepShape& s = shape_.shape(solid);
    const double spacing = 2 * M_PI * s.max_radius() / slices;
    return sweep_mesh(s, length, slices, spacing);
  };
  const int limb_slices = std::max(3, b.slices / 2);
  if (b.torso) {
    for (auto [solid, length, slices, out] :
         {std::make_tuple(int(BodyShape::kTorso), b.torso_length, b.slices, &torso_),
          std::make_tuple(int(BodyShape::kArmPlus), (b.shoulder - b.arm_bottom).norm(), limb_slices,
                          &arm_plus_)}) {
      const SweepMesh m = build(solid, length, slices);
      const SweepShape& s = shape_.shape(solid);
      for (std::size_t i = 0; i < m.t.size(); ++i) {
        out->vertices.push_back(s.point(m.t[i], m.theta[i], length));
        out->normals.push_back(s.normal(m.t[i], m.theta[i], length));
      }
      out->triangles = m.triangles;
    }
  }
  if (b.neck) {
    // The neck's length changes with the pose: its mesh is laid out for its rest length.
    const double rest = (b.neck_top - b.neck_bottom).norm();
    neck_ = build(BodyShape::kNeck, rest, limb_slices);
  }
  // Which triangles meet across each edge does not change with the pose (a rigid motion keeps
  // equal points equal): found once here for the occluders' depth bound.
  for (Mesh* m : {&head_, &torso_, &arm_plus_})
    if (!m->triangles.empty())
      m->neighbours =
          std::make_shared<const EdgeNeighbours>(edge_neighbours(m->vertices, m->triangles));
  if (b.neck) {
    const Mesh at_rest = neck_mesh((b.neck_top - b.neck_bottom).norm());
    neck_neighbours_ = std::make_shared<const EdgeNeighbours>(
        edge_neighbours(at_rest.vertices, at_rest.triangles));
  }
}

BodyModel::Mesh BodyModel::neck_mesh(double length) const {
  const SweepShape& s = shape_.shape(BodyShape::kNeck);
  Mesh m;
  for (std::size_t i = 0; i < neck_.t.size(); ++i) {
    m.vertices.push_back(s.point(neck_.t[i], neck_.theta[i], length));
    m.normals.push_back(s.normal(neck_.t[i], neck_.theta[i], length));
  }
  m.triangles = neck_.triangles;
  m.neighbours = neck_neighbours_;
  return m;
}

BodySurface BodyModel::placed(int part, int solid, const Mesh& m, const Eigen::Isometry3d& frame) {
  BodySurface s;
  s.part = part;
  s.solid = solid;
  s.vertices.reserve(m.vertices.size());
  for (const Vector3d& v : m.vertices) s.vertices.push_back(frame * v);
  s.normals.reserve(m.normals.size());
  for (const Vector3d& n : m.normals) s.normals.push_back(frame.linear() * n);
  s.triangles = m.triangles;
  s.neighbours = m.neighbours;
  return s;
}

std::vector<BodySurface> BodyModel::surfaces(const HeadPose& pose, const Vector3d& eye) const {
  const BodyParams& b = shape_.params();
  std::vector<BodySurface> out;
  if (b.torso) {
    const BodyShape::Placement torso = shape_.placement(pose, BodyShape::kTorso);
    BodyShape::Placement arm[2] = {shape_.placement(pose, BodyShape::kArmPlus),
                                   shape_.placement(pose, BodyShape::kArmMinus)};
    // An arm is behind the torso when its middle is farther from the eye than the torso's axis
    // at the same height.
    bool behind[2];
    for (int k = 0; k < 2; ++k) {
      const Vector3d mid = arm[k].frame * Vector3d(0, 0.5 * arm[k].length, 0);
      const Vector3d local = torso.frame.inverse() * mid;
      const Vector3d axis = torso.frame * Vector3d(0, local.y(), 0);
      behind[k] = (mid - eye).norm() > (axis - eye).norm();
    }
    for (int k = 0; k < 2; ++k)
      if (behind[k])
        out.push_back(placed(kBodyArm, BodyShape::kArmPlus + k, arm_plus_, arm[k].frame));
    out.push_back(placed(kBodyTorso, BodyShape::kTorso, torso_, torso.frame));
    for (int k = 0; k < 2; ++k)
      if (!behind[k])
        out.push_back(placed(kBodyArm, BodyShape::kArmPlus + k, arm_plus_, arm[k].frame));
  }
  if (b.neck) {
    const BodyShape::Placement at = shape_.placement(pose, BodyShape::kNeck);
    out.push_back(placed(kBodyNeck, BodyShape::kNeck, neck_mesh(at.length), at.frame));
  }
  if (b.head) out.push_back(head_surface(pose));
  return out;
}

BodySurface BodyModel::head_surface(const HeadPose& pose) const {
  return placed(kBodyHead, -1, head_, head_frame(pose));
}

double BodyModel::distance(const HeadPose& pose, const BodySurface& s, const Vector3d& x) const {
  if (s.solid < 0) return head_shape_.distance(pose.to_local(x));
  return shape_.solid_distance(s.solid, shape_.posed(pose), x);
}

std::vector<FaceStroke> BodyModel::face(const HeadPose& pose, const Camera& camera) const {
  // The lines lie on the head: its own surface within 3 mm of a sample does not hide it.
  return project_face(face_, pose, camera,
                      [&](const Vector3d& x) { return blocks(pose, camera.eye, x, 0.003); });
}

bool BodyModel::blocks(const HeadPose& pose, const Vector3d& eye, const Vector3d& x,
                       double ignore) const {
  if (shape_.blocks(pose, eye, x, 0, ignore)) return true;
  if (!params().head) return false;
  const double len = (x - eye).norm();
  if (len <= ignore) return false;
  return trace(eye, (x - eye) / len, len - ignore,
               [&](const Vector3d& p) { return head_shape_.distance(pose.to_local(p)); });
}

ProjectedBody BodyModel::project(const HeadPose& pose, const Camera& camera,
                                 const Vector3d& light_dir) const {
  const Vector3d light =
      light_dir.norm() > 1e-12 ? Vector3d(light_dir.normalized()) : Vector3d::Zero();
  const std::vector<BodySurface> world = surfaces(pose, camera.eye);
  // Each solid's signed distance, posed once for all the vertices of the later surfaces.
  const BodyShape::Posed posed = shape_.posed(pose);
  std::vector<std::function<double(const Vector3d&)>> solid;
  for (const BodySurface& s : world) {
    if (s.solid < 0)
      solid.push_back([&](const Vector3d& x) { return head_shape_.distance(pose.to_local(x)); });
    else
      solid.push_back(
          [&, k = s.solid](const Vector3d& x) { return shape_.solid_distance(k, posed, x); });
  }
  ProjectedBody out;
  constexpr double kNear = 1e-3;
  for (std::size_t i = 0; i < world.size(); ++i) {
    const BodySurface& s = world[i];
    ProjectedSurface p;
    p.part = s.part;
    const std::size_t n = s.vertices.size();
    std::vector<bool> in_front(n);
    p.pixel.resize(n);
    p.shade.resize(n);
    p.clearance.assign(n, std::numeric_limits<float>::infinity());
    p.local.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      const Vector3d& x = s.vertices[v];
      p.local[v] = s.solid < 0 ? pose.to_local(x) : Vector3d(posed.to_local[s.solid] * x);
      in_front[v] = (x - camera.eye).dot(camera.forward) >= kNear;
      p.pixel[v] = camera.project(x);
      p.shade[v] = float(std::clamp(0.5 * (1 + s.normals[v].dot(light)), 0.0, 1.0));
      for (std::size_t j = 0; j < i; ++j)
        p.clearance[v] = std::min(p.clearance[v], float(solid[j](x)));
    }
    for (const Eigen::Vector3i& t : s.triangles) {
      if (!in_front[t[0]] || !in_front[t[1]] || !in_front[t[2]]) continue;
      if (p.clearance[t[0]] <= 0 && p.clearance[t[1]] <= 0 && p.clearance[t[2]] <= 0) continue;
      const Eigen::Vector2d e1 = p.pixel[t[1]] - p.pixel[t[0]], e2 = p.pixel[t[2]] - p.pixel[t[0]];
      if (e1.x() * e2.y() - e1.y() * e2.x() < 0) p.triangles.push_back(t);
    }
    out.surfaces.push_back(std::move(p));
  }
  return out;
}

ProjectedBody project_body(const HeadPose& pose, const HeadGeometry& head, const BodyParams& body,
                           const CameraParams& camera, const Vector3d& light_dir) {
  return BodyModel(head, body).project(pose, Camera::look_at(camera), light_dir);
}

}  // namespace wisp::sim
