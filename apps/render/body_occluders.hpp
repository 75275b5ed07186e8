// The head and body as occluders of the hair (vector::Occluder): hair that passes behind them is
// cut exactly along their silhouettes by the arrangement, instead of being trimmed at whole
// strand samples. Each closed surface of the body model (head, neck, torso, arms) becomes one
// occluder: its silhouette is the convex hull of its projected vertices (which bounds the
// torso's concave trapezius slopes, or a mesh head, from outside), and its depth at a pixel is
// where the eye ray through the pixel first meets its triangles (+infinity on a miss, so a hull
// that bulges past the surface hides nothing).
#pragma once

#include <memory>
#include <vector>

#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/surface_rays.hpp"
#include "vector/arrangement.hpp"

namespace wisp::render {

// `bias` (scene units) is added to the occluders' depth: hair lies on the scalp, and a wisp's
// depth is that of its strand's centre line, so hair within `bias` behind the surface still
// counts as lying on it (use about a wisp's width). `head`: eye rays against the posed head
// (BodyModel::head_surface) to use for it, or null to build them here.
std::vector<vector::Occluder> body_occluders(const sim::BodyModel& body, const sim::HeadPose& pose,
                                             const sim::Camera& camera, double bias,
                                             std::shared_ptr<const sim::SurfaceRays> head = {});

}  // namespace wisp::render
