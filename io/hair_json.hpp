// Our JSON strand format: guide strands as polylines, for hand-made or exported hair models.
//   {"format": "wisp-strands", "version": 1, "strands": [[[x, y, z], ...], ...]}
// Points are root first, in metres in the head's frame (scene hair.file_scale / file_offset /
// file_z_up apply on top, as for .hair files). Unknown keys are errors.
#pragma once

#include <filesystem>
#include <vector>

#include "sim/hair_model.hpp"

namespace wisp::io {

// Throws std::runtime_error naming the file and the strand / point for bad content.
std::vector<sim::Polyline> read_strands_json(const std::filesystem::path& path);

// Writes atomically.
void write_strands_json(const std::filesystem::path& path,
                        const std::vector<sim::Polyline>& strands);

}  // namespace wisp::io
