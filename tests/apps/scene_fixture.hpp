// Scenes loaded once per test process, for tests that look inside single frames (hair base, fur,
// hatching): the saved animation of the scene (wisp::test::simulated) at a square size, and the
// frames at five head angles of its turn.
#pragma once

#include <string>
#include <vector>

#include "apps/render/scene_frames.hpp"

namespace wisp::test {

// `scene` loaded at size x size with its saved animation; kept for the test process.
const render::SceneFrames& loaded_scene(const std::string& scene, int size);

// Five frames spread over the head's turn: the extremes of its yaw, the middle, and between.
std::vector<int> five_angles(const sim::Animation& anim);

}  // namespace wisp::test
