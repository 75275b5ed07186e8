// A small reader of Wavefront OBJ triangle meshes for the head: `v x y z` and `f` lines (vertex
// indices, 1-based or negative, with or without /vt/vn parts; polygons are fanned into
// triangles). Everything else (normals, texture coordinates, groups, materials) is skipped.
#pragma once

#include <filesystem>

#include "sim/head.hpp"

namespace wisp::io {

// Throws std::runtime_error naming the file (and line) for a missing file or a malformed line.
sim::TriangleMesh read_obj(const std::filesystem::path& path);

}  // namespace wisp::io
