// How hair looks: wisp geometry plus the colours that become each wisp's diffusion curve. This is
// Faraj's look (2009, section 3.2.2): the hair colour inside every wisp, a shadow colour
// outside (so overlapping wisps shade each other), and one colour point, always on the same side
// of every wisp, which makes the hair look lit by a fixed light. The scene's `style` part fills
// it; the expressive styles (toon ramps, highlights, ink) extend it.
#pragma once

#include <Eigen/Core>

#include "vector/wisp.hpp"

namespace wisp::vector {

struct HairStyle {
  // A wisp stands for a clump of hair: about 2.8 cm wide at the root, so that some 150 guides
  // cover a head.
  WispStyle geometry = [] {
    WispStyle g;
    g.width = 0.028;
    return g;
  }();
  Eigen::Vector3f hair{0.42f, 0.25f, 0.13f};       // inside colour, linear RGB in [0,1]
  Eigen::Vector3f shadow{0.10f, 0.06f, 0.04f};     // outside colour
  Eigen::Vector3f highlight{0.80f, 0.58f, 0.34f};  // Faraj's colour point
  double highlight_along = 0.35;   // where the colour point sits along the wisp (0 root, 1 tip)
  double highlight_spread = 0.25;  // its extent along the wisp, as a fraction of the length
  bool highlight_on_left = true;   // which side of every wisp carries it
};

}  // namespace wisp::vector
