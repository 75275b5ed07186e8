// wisp-bench diffuse: the eight small-usvg drawings (data/drawings/external/), every primitive of
// them, rendered by wisp (read + rasterize + solve + anti-alias + blur, the best of `runs`) at
// the drawing's own size and at the size small-usvg's demo renders it, next to the time
// small-usvg took for that demo render. small-usvg's figures are not measured here (its code is
// not part of wisp): they are quoted from one run of its demo settings, described with the
// machine and commit in docs/diffusion.md.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/benches.hpp"
#include "diffusion/render.hpp"
#include "diffusion/timer.hpp"
#include "io/drawing_xml.hpp"

namespace wisp::bench {
namespace {

struct Reference {
  const char* name;
  int usvg_size;   // small-usvg's demo/main.cpp renders it at usvg_size^2
  double usvg_ms;  // its read + patches + solve at that size; < 0: not measured
};

// See docs/diffusion.md, "small-usvg": commit 4e7e997, 2 shared cores.
constexpr Reference kReferences[] = {
    {"bubble", 512, 266657}, {"crane", 512, 665938}, {"crane_ribbons", 512, -1},
    {"drape", 512, -1},      {"ladybug", 512, -1},   {"pepper", 512, -1},
    {"portal", 512, -1},     {"sunset", 256, -1},
};

double best_render_ms(const diffusion::Drawing& d, int width, int height, int runs) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = diffusion::Clock::now();
    diffusion::render_drawing(d, width, height);
    best = std::min(best, diffusion::ms_since(t0));
  }
  return best;
}

}  // namespace

int run_diffuse(const std::vector<std::string>& args) {
  const int runs = args.empty() ? 3 : std::max(1, std::stoi(args[0]));
  std::printf("{\n  \"benchmark\": \"diffuse\",\n  \"runs\": %d,\n  \"drawings\": [\n", runs);
  for (size_t k = 0; k < std::size(kReferences); ++k) {
    const Reference& ref = kReferences[k];
    const std::string path =
        std::string(WISP_SOURCE_DIR) + "/data/drawings/external/" + ref.name + ".xml";
    const auto t0 = diffusion::Clock::now();
    const io::DrawingFile f = io::read_drawing_xml(path);
    const double read_ms = diffusion::ms_since(t0);
    const diffusion::Drawing& d = f.drawing;
    std::fprintf(stderr, "diffuse: %s\n", ref.name);
    const double own = read_ms + best_render_ms(d, d.width, d.height, runs);
    const double at_usvg = read_ms + best_render_ms(d, ref.usvg_size, ref.usvg_size, runs);
    std::printf(
        "    {\"name\": \"%s\", \"size\": [%d, %d], \"curves\": %zu, \"poisson_curves\": %zu, "
        "\"meshes\": %zu, \"wisp_ms\": %.1f, \"usvg_size\": %d, \"wisp_ms_at_usvg_size\": %.1f",
        ref.name, d.width, d.height, d.curves.size(), d.poisson_curves.size(), d.meshes.size(), own,
        ref.usvg_size, at_usvg);
    if (ref.usvg_ms > 0)
      std::printf(", \"usvg_ms\": %.0f, \"speedup_at_usvg_size\": %.0f", ref.usvg_ms,
                  ref.usvg_ms / at_usvg);
    std::printf("}%s\n", k + 1 < std::size(kReferences) ? "," : "");
  }
  std::printf("  ]\n}\n");
  return 0;
}

}  // namespace wisp::bench
