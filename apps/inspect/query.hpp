// Questions the inspector answers about a frame, as plain text and JSON: what lies under a point
// (the face, its covering wisps with their depths there and the front-most one; the nearest
// arrangement edge with its sources, sides, parameter ranges and visibility; the wisp's
// attributes), and the whole arrangement of the frame as JSON for other tools (`--dump`).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/inspect/inspected_frame.hpp"

namespace wisp::inspect {

// The face containing p: its index in the view, or the unbounded face's.
int face_at(const vector::ArrangementView& view, const Eigen::Vector2d& p);

// Lines describing what lies under frame point p (pixels), for the side panel and stdout.
std::vector<std::string> describe_point(const InspectFrame& frame, const Eigen::Vector2d& p);

// The arrangement of the frame (layout in docs/inspect.md): wisps, faces (outline, holes,
// coverage, depth order), edges (sources, sides, parameter ranges, visibility) and vertices.
nlohmann::json dump_arrangement(const InspectFrame& frame);

}  // namespace wisp::inspect
