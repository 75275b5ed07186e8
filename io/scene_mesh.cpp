// OBJ reader: see scene_mesh.hpp.
#include "io/scene_mesh.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/input_file.hpp"

namespace wisp::io {
namespace {

// A head needs far fewer; these bound the collision shape's and the ray tests' work.
constexpr std::size_t kMaxVertices = 1000000, kMaxTriangles = 2000000;

}  // namespace

sim::TriangleMesh read_obj(const std::filesystem::path& path) {
  std::istringstream in(read_input_file(path, "OBJ file"));
  sim::TriangleMesh mesh;
  std::string line;
  int number = 0;
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++number;
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Eigen::Vector3d v;
      if (!(s >> v.x() >> v.y() >> v.z()) || !v.allFinite()) fail("expected a vertex 'v x y z'");
      if (mesh.vertices.size() >= kMaxVertices)
        fail("more than " + std::to_string(kMaxVertices) + " vertices");
      mesh.vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string item;
      while (s >> item) {
        const std::string head = item.substr(0, item.find('/'));
        long index = 0;
        try {
          std::size_t used = 0;
          index = std::stol(head, &used);
          if (used != head.size()) throw std::invalid_argument(head);
        } catch (const std::exception&) {
          fail("bad face index '" + item + "'");
        }
        const long n = static_cast<long>(mesh.vertices.size());
        const long resolved = index < 0 ? n + index : index - 1;
        if (index == 0 || resolved < 0 || resolved >= n)
          fail("face index " + std::to_string(index) + " refers to no vertex");
        face.push_back(static_cast<int>(resolved));
      }
      if (face.size() < 3) fail("a face needs at least 3 vertices");
      if (mesh.triangles.size() + face.size() > kMaxTriangles)
        fail("more than " + std::to_string(kMaxTriangles) + " triangles");
      for (std::size_t k = 1; k + 1 < face.size(); ++k)
        mesh.triangles.emplace_back(face[0], face[k], face[k + 1]);
    }
  }
  if (mesh.triangles.empty())
    throw std::runtime_error(path.string() + ": the OBJ file has no faces");
  return mesh;
}

}  // namespace wisp::io
