// SVG picture of a profile and its biarc tree (paper section 4.1, Figure 3 style):
// the input curve, the biarcs, their fat-arc error bands and the spiral split points.
#pragma once
#include <string>

#include "core/profile.h"
#include "fast/biarc_tree.h"

namespace revdist {

// A self-contained SVG document: the profile as a dense black polyline, the
// leaf biarcs in alternating colours, each leaf's band of half-width eps (drawn
// at least a few pixels wide when eps is invisible at this scale; the legend
// says so and gives the exaggeration), spiral split points as dots, piece joins
// as squares and the axis r = 0 dashed. `title` heads the legend.
std::string profile_svg(const std::string& title, const Profile& profile, const BiarcTree& tree);

}  // namespace revdist
