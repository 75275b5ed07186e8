// The saved animation (.wsim): what `wisp simulate` writes and the renderer reads back, bit for
// bit. Little-endian binary, version 1:
//   "WSIM"  u32 version = 1  u32 flags (bit 0: clump widths; no other bit is defined)
//   f64 fps  u32 frame_count  u32 strand_count  u32 samples[strand_count]
//   head: u32 shape (0 ellipsoid, 1 mesh)  f64 radii[3]
//         u32 vertex_count  u32 triangle_count  f64 vertices[3 V]  i32 triangles[3 T]
//   with flag bit 0: f64 widths[sum(samples)]  (sim::Animation::widths, metres)
//   per frame: u32 frame  f64 time  f64 head_position[3]  f64 head_rotation[4] (w, x, y, z)
//              f64 points[3 x sum(samples)]  (world metres, strand after strand, root first)
//   u64 checksum: FNV-1a 64 of every byte before it.
// Same simulation in, same bytes out: no timestamps, no padding.
#pragma once

#include <filesystem>

#include "sim/animation.hpp"

namespace wisp::io {

constexpr std::uint32_t kAnimVersion = 1;

// Writes atomically. Throws std::invalid_argument if frames disagree on the strand layout.
void write_animation(const std::filesystem::path& path, const sim::Animation& anim);

// Throws std::runtime_error naming the file: missing, not a .wsim, unknown version, truncated,
// trailing bytes, checksum mismatch (corrupt), or inconsistent content.
sim::Animation read_animation(const std::filesystem::path& path);

}  // namespace wisp::io
