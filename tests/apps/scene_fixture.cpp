// Scenes loaded once per test process (see scene_fixture.hpp).
#include "scene_fixture.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "run_command.hpp"

namespace wisp::test {

const render::SceneFrames& loaded_scene(const std::string& scene, int size) {
  static std::map<std::pair<std::string, int>, std::unique_ptr<render::SceneFrames>> cache;
  auto& slot = cache[{scene, size}];
  if (!slot) {
    render::SceneFramesOptions o;
    o.anim = simulated(scene);
    o.width = o.height = size;
    slot = std::make_unique<render::SceneFrames>(render::load_scene_frames(scene, o));
  }
  return *slot;
}

std::vector<int> five_angles(const sim::Animation& anim) {
  std::vector<std::pair<double, int>> yaw;
  for (int k = 0; k < int(anim.frames.size()); ++k) {
    const Eigen::Vector3d f = anim.frames[k].head.rotation * Eigen::Vector3d::UnitZ();
    yaw.emplace_back(std::atan2(f.x(), f.z()), k);
  }
  std::sort(yaw.begin(), yaw.end());
  std::vector<int> out;
  for (double q : {0.0, 0.25, 0.5, 0.75, 1.0})
    out.push_back(yaw[size_t(std::lround(q * (yaw.size() - 1)))].second);
  return out;
}

}  // namespace wisp::test
