// Validation of a profile chain (SPEC sections 2 and 3): pieces join, the chain
// reaches the axis at both ends or closes, r >= 0, no self-intersection.
// Used on every static profile and keyframe, and on every blended profile an
// instance uses (a blend of two good keyframes can dip below r = 0 or cross itself).
#pragma once
#include <string>

#include "core/profile.h"

namespace revdist {

// The bounding box of the profile's curve (r in lo.x..hi.x, z in lo.y..hi.y):
// every control point, and each arc's points at the quarter turns it passes
// (an arc given by three points may bulge far past them; the other pieces
// lie in the hull of their control points). Empty profile: lo = +inf, hi = -inf.
void profile_box(const Profile& profile, Vec2* lo, Vec2* hi);

// The profile's size: the diagonal of profile_box.
double profile_size(const Profile& profile);

// Tolerance for joins, axis contact and touching: 1e-9 * profile_size. Relative, so a
// case scaled by any factor is accepted or rejected alike; 1e-9 leaves ~7 digits of
// headroom above double rounding of coordinates of that size.
double profile_tolerance(const Profile& profile);

// Checks that consecutive pieces join within profile_tolerance and makes the joins
// exact (the next piece's first point becomes the previous piece's last point); then
// classifies the chain: both ends within tolerance of the axis -> closed_loop = false,
// ends snapped to r = 0 exactly; last end within tolerance of the first start ->
// closed_loop = true, end snapped to the start. Anything else is an InputError.
// `where` prefixes every message, e.g. "cases/x.json: solid \"vase\"".
void join_profile(Profile& profile, const std::string& where);

// Checks a joined profile (exact joins, as join_profile leaves them); throws InputError
// "<where> piece i: <problem>" or "<where>: <problem>". With tol = profile_tolerance:
//  - degenerate pieces (all control points within tol of each other) are rejected;
//  - r: an axis profile must have r >= -tol on every curve point, a closed loop r > tol.
//    PROVEN (up to the rounding of de Casteljau subdivision) for every piece kind: each
//    piece is converted to rational Bezier segments with positive weights, whose r lies in
//    the hull of the control r's; segments with a negative coefficient are subdivided until
//    the hull proves the bound or a curve point violates it (depth <= 40, then reported).
//  - self-intersection: pieces are cut into segments that are injective, proven by their
//    control polygon's edges lying in an open half-plane (variation diminishing with
//    positive weights); non-adjacent segments must stay more than tol apart, proven by
//    subdivision with chord-distance bounds (chord distance +- each segment's flatness,
//    which bounds its Hausdorff distance to its chord); adjacent segments must meet only
//    at their shared point, proven by a line through it separating their control points
//    after subdividing towards the joint. Undecided at the depth limit counts as touching.
//    Not tested: pairs of segments whose chain separation is below 4 * tol (only possible
//    around a cusp inside a piece, where splitting stops at size tol).
//  - a Bezier or B-spline piece must not stop inside its domain: its speed |C'| (sampled,
//    each local minimum refined) above 1e-9 of its control polygon's length per unit of
//    the domain, except within 1e-9 of the domain of its ends. A cusp, where the curve turns
//    back on itself, passes the self-intersection test (above) and has no tangent for the
//    spiral split and the fits' error bounds (its fits were left unproven: no finite answer).
void check_profile(const Profile& profile, const std::string& where);

}  // namespace revdist
