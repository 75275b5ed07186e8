// JSON strand format: see hair_json.hpp.
#include "io/hair_json.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "io/atomic_file.hpp"
#include "io/input_file.hpp"

namespace wisp::io {

std::vector<sim::Polyline> read_strands_json(const std::filesystem::path& path) {
  const std::string name = path.string();
  const nlohmann::json doc = parse_json(read_input_file(path, "strand file"), name);
  if (!doc.is_object()) throw std::runtime_error(name + ": expected a JSON object");
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key() != "format" && it.key() != "version" && it.key() != "strands")
      throw std::runtime_error(name + ": " + it.key() + ": unknown field");
  if (doc.value("format", std::string("wisp-strands")) != "wisp-strands")
    throw std::runtime_error(name + ": format: expected \"wisp-strands\"");
  if (doc.contains("version") && doc["version"] != 1)
    throw std::runtime_error(name + ": version: only version 1 is known");
  const auto strands = doc.find("strands");
  if (strands == doc.end() || !strands->is_array())
    throw std::runtime_error(name + ": strands: expected an array of strands");
  std::vector<sim::Polyline> out;
  for (std::size_t s = 0; s < strands->size(); ++s) {
    const auto& js = (*strands)[s];
    const std::string where = name + ": strands[" + std::to_string(s) + "]";
    if (!js.is_array() || js.size() < 2)
      throw std::runtime_error(where + ": expected at least 2 points");
    sim::Polyline line;
    for (std::size_t i = 0; i < js.size(); ++i) {
      const auto& p = js[i];
      if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() ||
          !p[2].is_number())
        throw std::runtime_error(where + "[" + std::to_string(i) + "]: expected [x, y, z]");
      const Eigen::Vector3d v(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      if (!v.allFinite())
        throw std::runtime_error(where + "[" + std::to_string(i) + "]: not finite");
      line.push_back(v);
    }
    out.push_back(std::move(line));
  }
  return out;
}

void write_strands_json(const std::filesystem::path& path,
                        const std::vector<sim::Polyline>& strands) {
  nlohmann::json doc = {{"format", "wisp-strands"}, {"version", 1}};
  nlohmann::json list = nlohmann::json::array();
  for (const auto& s : strands) {
    nlohmann::json line = nlohmann::json::array();
    for (const auto& p : s) line.push_back({p.x(), p.y(), p.z()});
    list.push_back(std::move(line));
  }
  doc["strands"] = std::move(list);
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream f(tmp);
    f << doc.dump() << "\n";
    if (!f) throw std::runtime_error(tmp.string() + ": write failed");
  });
}

}  // namespace wisp::io
