// Fuzz targets scenexml and curvesetxml: a drawing in either XML dialect (io/drawing_xml.cpp reads
// both), rendered at 24x24. The two targets are this one source; they differ in their seed
// corpora (SceneXML or CurveSetXML), and mutations may cross dialects.
#include "diffusion/render.hpp"
#include "io/drawing_xml.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = wisp::fuzz::write_input("drawing.xml", data, size);
  wisp::fuzz::expect_clean(data, size, [&] {
    const wisp::io::DrawingFile file = wisp::io::read_drawing_xml(path);
    wisp::diffusion::SolverOptions solver;
    wisp::diffusion::render_drawing(file.drawing, 24, 24, solver, nullptr, true);
  });
  return 0;
}
