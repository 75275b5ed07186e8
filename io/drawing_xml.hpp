// Reading and writing diffusion-curve drawings in the two XML dialects in use:
//
//  - `<!DOCTYPE CurveSetXML>`: the original format of Orzan et al.'s tool. Its `x` attribute is
//    the row and `y` the column, `R` holds blue and `B` red, and its left and right colour sets
//    are the other way round from ours (the x/y swap mirrors the picture). The reader undoes all
//    three, as small-usvg and the Qt renderers do.
//  - `<!DOCTYPE SceneXML>`: small-usvg's wrapper (`<scene image_width image_height>` around a
//    `<curve_set>`), with no swaps, optional `boundary="Neumann"` on a colour set, and colours as
//    `R G B` in 0..255 or `r g b` in [0,1].
//
// `globalID` is a position along the curve; each set is divided by its own largest globalID when
// that exceeds 1 (the convention of every reader). SceneXML also holds small-usvg's Poisson curves
// (`<poisson_curve_set>`: control points and RGB weights of any sign, with globalIDs) and gradient
// meshes (`<mesh_set>`: nb_rows x nb_cols tiles, positions, colours, optional
// `<pos_tangent_set>` of positionU/positionV, and the `normalized` flag), read and written as
// given; CurveSetXML cannot hold them.
//
// Errors are std::invalid_argument with "FILE:LINE: <element>: what is wrong".
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "diffusion/diffusion_curve.hpp"

namespace wisp::io {

enum class XmlDialect { SceneXML, CurveSetXML };

struct DrawingFile {
  diffusion::Drawing drawing;
  XmlDialect dialect = XmlDialect::SceneXML;
  std::vector<std::string> warnings;  // stale counts (see check_count in the reader)
};

constexpr int kMaxImageSide = 16384;

DrawingFile read_drawing_xml(const std::filesystem::path& path);
DrawingFile parse_drawing_xml(const std::string& text, const std::string& name);

// SceneXML keeps every value exactly (colours as r g b floats, globalID as the parameter itself).
// CurveSetXML writes what the original tools read: 0..255 colours and integer globalIDs out of
// 10000, so its values round to 1/255 and 1e-4. Written atomically.
void write_drawing_xml(const diffusion::Drawing& drawing, const std::filesystem::path& path,
                       XmlDialect dialect = XmlDialect::SceneXML);
std::string format_drawing_xml(const diffusion::Drawing& drawing, XmlDialect dialect);

}  // namespace wisp::io
