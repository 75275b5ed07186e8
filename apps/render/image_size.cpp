// parse_size (see image_size.hpp).
#include "apps/render/image_size.hpp"

#include <regex>
#include <stdexcept>

#include "io/drawing_xml.hpp"

namespace wisp::render {

std::pair<int, int> parse_size(const std::string& option, const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,6})x(\d{1,6}))")))
    throw std::invalid_argument(option + ": expected WxH, for example 512x512, got '" + text + "'");
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 1 || h < 1 || w > io::kMaxImageSide || h > io::kMaxImageSide)
    throw std::invalid_argument(option + " " + text + ": each side must be between 1 and " +
                                std::to_string(io::kMaxImageSide));
  return {w, h};
}

}  // namespace wisp::render
