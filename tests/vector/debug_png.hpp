// Debug pictures of an arrangement for looking at test scenes (not assertions): faces filled by
// front-most wisp, visible outline pieces in white, hidden ones in dark red, intersections as
// dots; and a label raster as colours. Written only when WISP_DEBUG_PNG names a folder.
#pragma once

#include <string>

#include "tests/vector/raster_reference.hpp"
#include "vector/arrangement.hpp"

namespace wisp::test {

// The folder from WISP_DEBUG_PNG, or "" when unset.
std::string debug_png_dir();

void write_arrangement_png(const std::string& path, const vector::ArrangementView& view, int width,
                           int height, int scale = 2);
void write_raster_png(const std::string& path, const Raster& raster);
// Pixels where a and b differ in white over a dimmed a.
void write_diff_png(const std::string& path, const Raster& a, const Raster& b);

}  // namespace wisp::test
