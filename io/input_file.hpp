// Input files read whole, each refused in one line naming it before anything is sized by its
// content: a folder, a device or a missing file, a file above the size limit, JSON nested deeper
// than any of our formats needs. Every reader in io/ goes through here, so the limits are one
// table (docs/robustness.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace wisp::io {

// The largest input file read (scene, style, strands, .hair, OBJ, drawing, .wsim, ramp).
constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t(1) << 30;  // 1 GiB
// The deepest nesting of JSON arrays and objects accepted (our formats need 4).
constexpr int kMaxJsonDepth = 32;

// The bytes of `path`. Throws std::runtime_error "path: <what> is a folder, not a file" and the
// like; `what` names the kind of file ("scene file").
std::string read_input_file(const std::filesystem::path& path, const std::string& what);

// Parses JSON text; throws std::invalid_argument "name: invalid JSON: <where and why>" (one line,
// without the library's error id) or "name: JSON nested deeper than 32 levels".
nlohmann::json parse_json(const std::string& text, const std::string& name);

// At most `max` characters of `value` as JSON, for messages ("[[[[[[...").
std::string json_excerpt(const nlohmann::json& value, std::size_t max = 60);

}  // namespace wisp::io
