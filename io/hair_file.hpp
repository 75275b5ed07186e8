// Cem Yuksel's .hair format (cemyuksel.com/research/hairmodels), read and written. A 128-byte
// header ("HAIR", strand count, point count, array bit flags, default segments, thickness,
// transparency, colour, 88 bytes of text), then, in this order, the arrays its flags say are
// present: segments (uint16 per strand), points (3 float32 per point, root first), thickness,
// transparency (float32 per point) and colours (3 float32 per point). Absent arrays take the
// header's defaults. Little-endian, as every published model.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/hair_model.hpp"

namespace wisp::io {

struct HairFile {
  std::vector<sim::Polyline> strands;   // file units, root first
  bool has_segments = true;             // the segments array is present (else d_segments)
  std::vector<float> thickness;         // per point, empty when the array is absent
  std::vector<float> transparency;      // per point, empty when absent
  std::vector<Eigen::Vector3f> colors;  // per point, empty when absent
  std::uint32_t default_segments = 0;
  float default_thickness = 1.0f;
  float default_transparency = 0.0f;
  Eigen::Vector3f default_color{1.0f, 1.0f, 1.0f};
  std::string info;  // up to 88 bytes
};

// Throws std::runtime_error naming the file: missing, bad signature, inconsistent counts,
// truncated or with trailing bytes.
HairFile read_hair_file(const std::filesystem::path& path);

// Writes `hair` (atomically). Throws std::invalid_argument if the per-point arrays do not match
// the point count, a strand has more than 65535 segments, or has_segments is false while strands
// differ from default_segments.
void write_hair_file(const std::filesystem::path& path, const HairFile& hair);

}  // namespace wisp::io
