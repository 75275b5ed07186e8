// The facial features' geometry (see face.hpp).
#include "sim/face.hpp"

#include <array>
#include <cmath>

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

// A control point: azimuth and elevation in degrees, width in millimetres.
using Control = std::array<double, 3>;

// The features for a head facing +z, +x on the viewer's right. Mirrored ones are given for
// the +x side. Sized for the default head (radii 7.8 x 10.5 x 9.5 cm), where 1 degree is
// about 1.6 mm on the face.
struct Line {
  Feature feature;
  std::vector<Control> controls;
  bool mirrored;
};
const std::vector<Line>& lines() {
  static const std::vector<Line> table = {
      // Brows: a gentle arch, thickest a third of the way out.
      {Feature::Brow, {{7, 13, 1.6}, {17, 16.5, 2.6}, {27, 15, 1.8}, {33, 11.5, 0.6}}, true},
      // Upper lids, heavier towards the outer corner.
      {Feature::Lid, {{9, -0.5, 0.8}, {17, 3, 2.0}, {26, 2, 2.4}, {31, -1.5, 0.8}}, true},
      // Irises: a short thick stroke under the lid, round caps make it an oval.
      {Feature::Iris, {{18.5, 0.5, 5.2}, {18.5, -1.2, 5.6}, {18.5, -2.8, 5.0}}, true},
      // Nose: down the side away from the light, hooking under the tip.
      {Feature::Nose,
       {{5, -9, 0.6}, {6, -15, 1.4}, {5, -20.5, 1.6}, {1, -22.5, 1.4}, {-3, -21.5, 0.6}},
       false},
      // Mouth: a slight smile, and a short stroke for the lower lip.
      {Feature::Mouth,
       {{-13, -34, 0.6}, {-6, -36.5, 1.8}, {0, -37, 2.0}, {6, -36.5, 1.8}, {13, -34, 0.6}},
       false},
      {Feature::Mouth, {{-4, -41.5, 0.6}, {0, -42, 1.3}, {4, -41.5, 0.6}}, false},
  };
  return table;
}

// Uniform Catmull-Rom through the controls (ends doubled), `per` samples per span.
std::vector<Control> sample(const std::vector<Control>& c, int per) {
  std::vector<Control> out;
  const int n = int(c.size());
  for (int i = 0; i + 1 < n; ++i) {
    const Control& p0 = c[std::max(i - 1, 0)];
    const Control& p1 = c[i];
    const Control& p2 = c[i + 1];
    const Control& p3 = c[std::min(i + 2, n - 1)];
    for (int k = 0; k < per || (i + 2 == n && k == per); ++k) {
      const double u = double(k) / per, u2 = u * u, u3 = u2 * u;
      Control q;
      for (int d = 0; d < 3; ++d)
        q[d] = 0.5 *
               (2 * p1[d] + (p2[d] - p0[d]) * u + (2 * p0[d] - 5 * p1[d] + 4 * p2[d] - p3[d]) * u2 +
                (3 * p1[d] - p0[d] - 3 * p2[d] + p3[d]) * u3);
      out.push_back(q);
    }
  }
  return out;
}

}  // namespace

std::vector<FaceLine> face_lines(const HeadShape& head) {
  std::vector<FaceLine> out;
  for (const Line& f : lines())
    for (int side : f.mirrored ? std::vector<int>{1, -1} : std::vector<int>{1}) {
      FaceLine line;
      line.feature = f.feature;
      for (const Control& c : sample(f.controls, 8)) {
        const double az = side * c[0] * M_PI / 180, el = c[1] * M_PI / 180;
        const Vector3d dir(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
        const Vector3d p = head.surface_point(dir);
        Vector3d n;
        head.distance(p, &n);
        line.points.push_back(p);
        line.normals.push_back(n);
        line.width.push_back(c[2] * 1e-3);
      }
      out.push_back(std::move(line));
    }
  return out;
}

}  // namespace wisp::sim
