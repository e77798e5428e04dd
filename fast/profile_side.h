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
// Decided by the parity of a ray's crossings, part by part: a node whose
// capsule misses the ray and stays farther than `margin` from q holds a part
// of the true curve that does not cross the ray (not descended; a lazy tree's
// pending nodes there are never built); a leaf the ray may meet counts its
// biarc's crossings, which are the true part's when q is farther than `margin`
// + the leaf's eps from the biarc (the true part lies within eps of it and
// shares its end points, so it cannot separate q from where the biarc puts
// it); a leaf nearer than that makes the answer unknown.
Side profile_side(BiarcTreeView& tree, const Vec2& q, double margin);

}  // namespace revdist
