// Whole input files and JSON text with limits: see input_file.hpp.
#include "io/input_file.hpp"

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace wisp::io {

namespace fs = std::filesystem;

std::string read_input_file(const fs::path& path, const std::string& what) {
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    throw std::runtime_error(name + ": cannot open the " + what + ": no such file");
  if (fs::is_directory(status))
    throw std::runtime_error(name + ": is a folder; expected a " + what);
  if (!fs::is_regular_file(status))
    throw std::runtime_error(name + ": not a regular file; expected a " + what);
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw std::runtime_error(name + ": cannot read the " + what);
  if (size > kMaxInputBytes)
    throw std::runtime_error(name + ": " + std::to_string(size >> 20) + " MiB; a " + what +
                             " may have at most " + std::to_string(kMaxInputBytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(name + ": cannot open the " + what);
  std::string bytes;
  bytes.resize(std::size_t(size));
  in.read(bytes.data(), std::streamsize(size));
  if (in.gcount() != std::streamsize(size))
    throw std::runtime_error(name + ": cannot read the " + what);
  return bytes;
}

nlohmann::json parse_json(const std::string& text, const std::string& name) {
  using nlohmann::json;
  const json::parser_callback_t depth = [&](int level, json::parse_event_t, json&) {
    if (level > kMaxJsonDepth)
      throw std::invalid_argument(name + ": JSON nested deeper than " +
                                  std::to_string(kMaxJsonDepth) + " levels");
    return true;
  };
  try {
    return json::parse(text, depth);
  } catch (const json::exception& e) {
    // nlohmann's message carries the line and column (or the overflowing number) after its id.
    const std::string what = e.what();
    const auto at = what.find("] ");
    throw std::invalid_argument(
        name + ": invalid JSON: " + (at == std::string::npos ? what : what.substr(at + 2)));
  }
}

std::string json_excerpt(const nlohmann::json& value, std::size_t max) {
  std::string text = value.dump();
  if (text.size() > max) text = text.substr(0, max) + "...";
  return text;
}

}  // namespace wisp::io
