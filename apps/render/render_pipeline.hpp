// One frame of the main job, from projected strands to a finished picture:
//   wisps (vector/) -> arrangement: visibility, hair mask (vector/, CGAL), with the hair base
//   behind the wisps (vector/hair_base.hpp) -> diffusion curves
//   in the style: the visible outline pieces, lit by the frame's light, and curves inside the
//   wisps for toon bands and highlights (vector/hair_curves) -> rasterize + multigrid solve
//   (diffusion/, warm-started from the previous frame) -> layers of an FramePicture, with
//   ink strokes along the silhouette and occlusion lines (vector/ink_strokes), and, when the
//   style or the lens blurs, the blur map of the outlines' blur values (vector/hair_blur), and
//   hatch strokes in the hair's shadows (vector/hatching).
// Used by `wisp render` for every frame and by the inspector for the one it shows.
#pragma once

#include <vector>

#include "apps/render/body_hatching.hpp"
#include "apps/render/body_paths.hpp"
#include "apps/render/picture.hpp"
#include "diffusion/antialias.hpp"
#include "diffusion/multigrid.hpp"
#include "diffusion/rasterize.hpp"
#include "sim/projected.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_blur.hpp"
#include "vector/hair_curves.hpp"
#include "vector/hair_style.hpp"
#include "vector/hatching.hpp"
#include "vector/ink_strokes.hpp"

namespace wisp::render {

struct FrameSetup {
  vector::HairStyle style;
  diffusion::SolverOptions solver;
  Rgb background{1, 1, 1};
  bool keep_faces = false;         // keep the arrangement's faces in FrameResult (the inspector)
  bool flat_regions = false;       // compute the per-wisp regions of flat SVGs
  bool antialias = true;           // mix both sides' colours where visible curves cross pixels
  bool whole_image_solve = false;  // solve every pixel, not the curves' window (for comparison)
  vector::Lens lens;               // depth of field (vector/hair_blur.hpp); aperture 0: none
};

// Milliseconds per stage.
struct FrameTimings {
  double wisps = 0, arrangement = 0, curves = 0, rasterize = 0, solve = 0, total = 0;
  double ink = 0;        // fitting the ink strokes
  double antialias = 0;  // re-sampling the pixels that visible curves cross
  double blur = 0;       // the blur values and the blur map's solve
  double hatching = 0;   // laying and clipping the hatch strokes
  double body = 0;       // before the hair: the body's paths and occluders, the hair base
};

// A frame's plain solve: what anti-aliasing reads and what the next frame's solve starts from.
// Only the colour solve's window is kept (the solution is 0 outside it, see FrameResult::window),
// so a frame holds no whole-image copy of it.
struct FrameSolution {
  int width = 0, height = 0;      // the image's
  diffusion::PixelWindow window;  // of the colour solve (FrameResult::window)
  std::vector<float> colours;     // three planes of window.pixel_count() floats
  std::vector<float> blur;        // the blur map's solve, width x height, or empty
};

struct FrameResult {
  FramePicture picture;
  std::vector<vector::Wisp> wisps;
  vector::WispArrangement arrangement;
  std::vector<diffusion::DiffusionCurve> curves;  // outlines first, then curves inside wisps
  vector::HairCurveStats curve_stats;             // how many of each kind
  int base_curves = 0;                            // the hair base's, after the others
  std::vector<vector::InkCurve> ink;              // the strokes of picture.ink, as fitted
  std::vector<vector::HatchStroke> hatching;      // picture.hatching's on the hair, then
  std::vector<BodyHatch> body_hatching;           // its strokes on the body
  // The pixels the colour solve covered: the curves' window (see render_solve). The problem and
  // the solver's residuals are of its size; the solution outside it is 0, since the hair mask
  // and the anti-aliasing never show a pixel that far from every curve.
  diffusion::PixelWindow window;
  diffusion::Problem problem;  // the rasterized constraints (inspector): only with keep_faces
  diffusion::SolveStats solve;
  diffusion::AntialiasStats antialias;
  FrameSolution solution;  // the next frame's warm start
  FrameTimings time;
};

// `body`: the head and body drawn under the hair; `occluders`: the same as occluders of the hair
// (apps/body_occluders.hpp). With occluders every strand becomes a whole wisp and the
// arrangement cuts it along their silhouettes, so hair slides behind the head continuously
// instead of losing whole samples; without, wisps keep the samples the camera marked visible.
// `base`: the hair base of the frame (scene_frames.hpp: frame_base), or empty for none.
// `warm_start`: the previous frame's solution (same image size) or null. `neighbour`: the frame
// before (or after, for the first), for the blur's motion (vector::BlurSources); null: no motion.
FrameResult render_frame(const sim::ProjectedFrame& frame, BodyLayer body,
                         std::vector<vector::Occluder> occluders, vector::HairBase base,
                         const FrameSetup& setup, const FrameSolution* warm_start,
                         const sim::ProjectedFrame* neighbour = nullptr);

// render_frame in its two halves, for renderers that overlap frames (render_range.hpp): the
// geometry (wisps, arrangement, curves, ink, hatching) depends on the frame alone; the shading
// (rasterized constraints, solve, anti-aliasing, blur) on the previous frame's solution too.
// render_shading completes what render_geometry returned, with the same arguments as above.
FrameResult render_geometry(const sim::ProjectedFrame& frame, BodyLayer body,
                            std::vector<vector::Occluder> occluders, vector::HairBase base,
                            const FrameSetup& setup);
void render_shading(FrameResult& r, const sim::ProjectedFrame& frame, const FrameSetup& setup,
                    const FrameSolution* warm_start,
                    const sim::ProjectedFrame* neighbour = nullptr);

// render_shading in its two halves: render_solve is what the next frame's warm start depends on
// (the rasterized constraints, the solve, the blur map's solve; r.solution is the warm start);
// render_finish depends on this frame alone (anti-aliasing from the plain solve `solved`:
// r.solution, or the FrameSolution the caller moved it into to share it with the next frame's warm
// start; and the re-blur), so frames may finish in parallel.
void render_solve(FrameResult& r, const sim::ProjectedFrame& frame, const FrameSetup& setup,
                  const FrameSolution* warm_start, const sim::ProjectedFrame* neighbour = nullptr);
void render_finish(FrameResult& r, const FrameSetup& setup, const FrameSolution& solved);

}  // namespace wisp::render
