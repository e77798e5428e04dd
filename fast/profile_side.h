// Which side of a profile a point of the meridian half-plane lies on: the
// point-in-solid test behind the solid semantics of SPEC section 2 (distance 0
// when one solid contains the other, "overlap" only when a shared point is
// proven).
#pragma once
#include "core/vec.h"
#include "fast/biarc_tree.h"

namespace revdist {

enum class Side { inside, outside, unknown };

// Side of local point q = (r, z), r >= 0, for the region bounded by the tree's
// profile (closed with the axis segment when the profile ends on the axis).
// Decided on the biarcs by ray crossing; the answer holds for the true profile
// when q is farther than `margin` + every leaf's eps from the biarcs (the true
// curve lies within eps of them, so it cannot separate q from where the biarcs
// put it). Otherwise unknown.
Side profile_side(const BiarcTree& tree, const Vec2& q, double margin);

}  // namespace revdist
