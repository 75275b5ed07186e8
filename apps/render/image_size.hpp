// Image sizes given on a command line ("--size 512x512"), shared by `wisp` and wisp-inspect. In a
// file of its own so that a command needing only this (wisp diffuse) does not link the scene's
// frames, and with them the simulation.
#pragma once

#include <string>
#include <utility>

namespace wisp::render {

// "WxH" -> (W, H), each side 1 to io::kMaxImageSide. Throws std::invalid_argument naming `option`.
std::pair<int, int> parse_size(const std::string& option, const std::string& text);

}  // namespace wisp::render
