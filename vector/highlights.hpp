// Stylised highlights as closed shapes in a wisp's chart (t, u), turned into closed diffusion
// curves by vector/inner_curves.cpp.
//  - Band (Costigan 2013, section 4.3.6): the region of the tube where the Blinn term
//    (N(u).H)^c exceeds a threshold. Along the strand it peaks where the tangent is perpendicular
//    to H (the Kajiya-Kay peak), so neighbouring wisps light up at consistent places and the
//    highlights line up into a band across the hair.
//  - Anime (Shin 2006, section 5.4.2, after Anjyo and Hiramitsu): Shin's specular
//    max(L.W, 0)^n, W = normalize(w N + (1 - w) T) (T towards the root, N the outward normal
//    from the head's centre) is sampled along each wisp's centre; the samples over the threshold
//    give a candidate stretch per wisp; candidates whose peaks lie close together on screen are
//    linked across neighbouring wisps (Shin's merged points and triangle strips), and clusters
//    of too few wisps are dropped. Each kept candidate becomes a zigzag shape: teeth pointing
//    towards the tip along its lower edge, shallow notches along its upper edge, so the cluster
//    reads as one jagged anime band.
// All shapes are polygons in (t, u), counter-clockwise (inside on the left), within
// |u| <= max_width, so they stay inside their wisp.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "vector/hair_style.hpp"
#include "vector/wisp_chart.hpp"

namespace wisp::vector {

using ChartPolygon = std::vector<Eigen::Vector2d>;

// Band highlights of one wisp: closed level sets of the Blinn term at `style.threshold`, sampled
// at the chart parameters `ts` and 17 lateral positions.
std::vector<ChartPolygon> band_highlights(const WispChart& chart, const std::vector<double>& ts,
                                          const HighlightStyle& style,
                                          const Eigen::Vector3d& light);

struct AnimeCandidate {
  int wisp = -1;
  double t0 = 0, t1 = 0, t_peak = 0;  // the stretch over the threshold and its peak
  Eigen::Vector2d peak_px{0, 0};      // the peak on screen
};

// The stretch of the wisp's centre over the threshold that holds the highest sample, if any.
std::optional<AnimeCandidate> anime_candidate(const WispChart& chart, const std::vector<double>& ts,
                                              const HighlightStyle& style,
                                              const Eigen::Vector3d& light,
                                              const Eigen::Vector3d& head_centre);

// Per candidate: its cluster (candidates linked when their peaks are at most `link_px` apart),
// or -1 when the cluster has fewer than `min_cluster` members.
std::vector<int> cluster_candidates(const std::vector<AnimeCandidate>& candidates, double link_px,
                                    int min_cluster);

// The zigzag shape of a kept candidate.
ChartPolygon anime_zigzag(const AnimeCandidate& c, const HighlightStyle& style);

}  // namespace wisp::vector
