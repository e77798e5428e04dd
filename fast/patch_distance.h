// Distance between two patches of revolution (toroidal or conical), the leaf
// kernel of the distance query (paper section 3, "l +- r1 +- r2", extended to
// patch boundaries, cones and intersection).
//
// Every critical pair (x, y), x != y, of |x - y| on two patches lies on a line
// normal to both: interior-interior pairs on a binormal of the major circles
// (torus-torus), a normal of a cone through a critical point of a major circle
// (torus-cone, fast/cone_normals.h) or a common normal of two cones; a boundary
// circle against an interior on a binormal of the circle and the major circle
// or a circle-cone normal; boundary against boundary at a circle-circle
// distance. The minimum over those candidates is the distance unless the
// patches intersect. Intersection is excluded by the sign of the other patch's
// surface function (|q - c| - rho, or n . q - off) over the patch: its extremes
// lie at the same candidate points plus the points where the patch crosses the
// other solid's axis or the other torus's major circle (where that function is
// not smooth). Cones and flat annuli lie on unbounded surfaces that a patch may
// cross far from the other patch; the patches' bounding tori (patch_disk) being
// disjoint separates them too.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "fast/patch.h"

namespace revdist {

// End circles that are boundaries (patch_pair_distance's `outer`).
constexpr unsigned kOuterA0 = 1, kOuterA1 = 2, kOuterB0 = 4, kOuterB1 = 8, kOuterAll = 15;

struct PatchPairResult {
  double upper = 0.0;     // |x - y| of the best candidate: genuine points of both patches (to rounding)
  Vec3 x = Vec3::Zero();  // on patch A
  Vec3 y = Vec3::Zero();  // on patch B
  bool found = false;     // some candidate pair exists (always, unless a patch is empty)
  // Proven (to rounding) that the patches do not meet: then `upper` is their distance.
  bool separated = false;
  // An infinite family of critical lines (coaxial or Villarceau major circles,
  // a degenerate cone system): `upper` is valid, but the distance may be smaller.
  bool degenerate = false;
  // Where the other patch's surface function is smallest and largest over each
  // patch: the points most likely to lie inside the other solid when the
  // patches cross (probes for an overlap proof).
  Vec3 a_low = Vec3::Zero(), a_high = Vec3::Zero();  // on A, extremes of B's function
  Vec3 b_low = Vec3::Zero(), b_high = Vec3::Zero();  // on B, extremes of A's function
  // Lower bound of the sub-problems skipped because they could not come below
  // the cutoff (+inf when none was): when separated, the patch distance is
  // min(upper, lower_skipped) or more.
  double lower_skipped = std::numeric_limits<double>::infinity();
};

// cutoff: when the patches are proven apart (disjoint bounding tori, or
// known_lower > rounding), parts of the enumeration proven (by circle
// distances) to stay at or above cutoff are skipped; pass the caller's current
// upper bound. +inf: everything. known_lower: a lower bound on the patches'
// distance the caller already has (patch_pair_quick's), -inf when none.
//
// outer: which end circles are boundaries of the caller's surfaces (kOuter*
// bits). A patch that continues G1 into another one the caller compares too
// (the two arcs of one biarc) ends there in a junction circle, not a boundary.
// Once the patches are proven apart, sub-problems on junction circles are
// skipped: a closest pair of the G1 unions that lies on a junction is a
// critical pair of the unions, normal to both arcs there, so the interior
// enumeration of either arc pair finds it (angular ranges are closed) or that
// arc pair's own bound covers it. The result then bounds the unions' distance,
// not this patch pair's alone.
PatchPairResult patch_pair_distance(const Patch& A, const Patch& B,
                                    double cutoff = std::numeric_limits<double>::infinity(),
                                    double known_lower = -std::numeric_limits<double>::infinity(),
                                    unsigned outer = kOuterAll);

// A cheap proof that patches P and Q do not meet (no common point), for pairs
// whose bounding tori meet: P is cut into boxes (profile range x azimuth
// range, 16 sectors to start), each held by a ball; a box is cleared when its
// ball misses Q's bounding torus or Q's whole surface (1-Lipschitz functions
// evaluated at the ball's centre, `margin` for rounding), else split. True
// when every box clears within `budget` evaluations; false means "not
// proven", not "they meet".
bool patches_apart(const Patch& P, const Patch& Q, double margin, int budget);

// A proof that patches P and Q are at least `cut` apart, without the
// enumeration of critical lines: the local, certified kernel in front of
// patch_pair_distance. The distance from a point x to Q's patch is the plane
// distance from x's (rho, z) in Q's meridian half-plane to Q's arc or segment
// (the nearest point of a full surface of revolution shares x's half-plane):
// the distance to the arc's circle (or the segment's line) when x's
// direction from its centre (or its projection) falls in the arc (segment),
// else to the nearer end. The boxes of the smaller patch (profile range x
// azimuth range, from 8 sectors) are bounded by that function at the box's
// centre less a first- or second-order remainder (as in patches_apart), or,
// for a box whose ball stays clear of Q's bounding disk, by that disk, and
// split until every box clears `cut` or the budget is spent. True when every
// box clears: *lower is then the least box bound (>= cut), a lower bound on
// the patches' distance. False ("not proven") when a box's centre is closer
// than cut (the pair really is) or the budget runs out; *evals counts boxes.
// margin: the rounding allowance of the evaluations (a few ulps of the
// coordinates).
// closer: when the proof fails because a box's centre is closer than cut, that
// centre's parameters (profile fraction u, azimuth about P's axis as measured
// by patch_point), a start for patch_pair_descent.
// seen: when the proof fails otherwise (the budget runs out, or boxes too
// small to clear), the parameters of the box centre nearest Q so far; the
// start for a descent that may find the pair's minimum (and so a better
// upper bound, at which the proof can pass). Infinite when the proof passes
// or meets a closer point.
bool patches_at_least(const Patch& P, const Patch& Q, double cut, double margin, int budget, double* lower,
                      int* evals = nullptr, Vec2* closer = nullptr, Vec2* seen = nullptr);

// A proof that patches W and T are at least `cut` apart from a circle of T
// alone, first T's major circle (a toroidal T): every point of T lies within
// rho_T of that circle, so dist(W, T) >= min over the circle of dist(y, W) -
// rho_T, a one-dimensional minimum of a closed-form distance (W's, in y's
// meridian half-plane). Its window is W's own: where T's full torus stays
// near the solid's true surface (as it does beside the arc, within the fit's
// error there), the bound is about the distance from W to the other solid,
// which a neighbour of the closest pair clears by far where the full tori
// (patch_pair_quick) meet.
// The circle is cut into arcs (quarters to start), bounded from the distances
// at their ends: for any set, |y - m|^2 - dist(y)^2 is convex in y (a maximum
// of functions affine in y), so along a chord of length L and middle m with
// end distances d0, d1, dist^2 stays at or above the least over t in [0, 1] of
// (t - 1/2)^2 L^2 - L^2 / 4 + (1 - t) d0^2 + t d1^2 (no loss on a slope,
// |d1^2 - d0^2| >= L^2, and L^2 / (8 d) at a minimum), and the arc lies
// within its sagitta of the chord. Arcs are halved until each clears the cut
// or the budget of evaluations is spent. True when every arc clears: *lower
// is then the least arc bound (>= cut). When the major circle's bound fails,
// the same bound is tried, with a budget of its own, on the circle that the
// centre of T's bounding disk sweeps (patch_disk), with the disk's radius for
// rho_T: every point of T lies within it of that circle at its own azimuth.
// Where that disk is the thinner tube (a short or flat arc, whose circle lies
// far out; a segment, which has none) it proves what the major circle cannot.
// False ("not proven") when a point of each circle tried is closer than cut
// plus its tube, or the budgets run out. margin: the rounding allowance of
// the evaluations. hint: a point near where the patches are closest (a
// query's witness), where the cutting starts.
bool patch_spine_at_least(const Patch& W, const Patch& T, double cut, double margin, int budget, double* lower,
                          int* evals = nullptr, const Vec3* hint = nullptr);

// The chord lemma of the spine proofs: where the distances from some set of
// two points L apart (L2 = L^2) are d0 and d1, the set avoids both open
// balls, so the segment between the points is at least the returned value
// from it (the rim of the balls' meeting; the nearer ball's radius where one
// ball covers the other's centre). Negative distances count as 0. (Inline:
// the spine proofs' inner loop.)
inline double chord_bound(double d0, double d1, double L2) {
  d0 = std::max(d0, 0.0), d1 = std::max(d1, 0.0);
  const double q0 = d0 * d0, q1 = d1 * d1, dq = q1 - q0;
  const double chord2 =
      std::abs(dq) >= L2 ? std::min(q0, q1) : 0.5 * (q0 + q1) - 0.25 * L2 - (L2 > 0 ? 0.25 * dq * dq / L2 : 0.0);
  return std::sqrt(std::max(0.0, chord2));
}

// The same proof for any set S that lies within `tube` of circle `spine` at
// its own azimuth (the spine's normal is its axis; a part of a solid about
// that axis, within its bounding disk of radius `tube`, is such a set): true
// when every point of S is at least cut from W (*lower, >= cut, then bounds
// that distance), false when not proven. Where W is much longer than S's
// disk, W's own surface stands in for its loose bounding torus.
bool patch_circle_at_least(const Patch& W, const Circle3& spine, double tube, double cut, double margin, int budget,
                           double* lower, int* evals = nullptr, const Vec3* hint = nullptr);

// The point of patch P at profile fraction u in [0, 1] and azimuth th (from a
// fixed direction normal to P's axis).
Vec3 patch_point(const Patch& P, double u, double th);

// The box of P's parameters [um - du, um + du] x [tm - dt, tm + dt] (profile
// fraction and azimuth, as in patch_point) as the local proofs bound it: its
// centre x, the radius of a ball around x holding the box, and bounds on the
// speed and on half the acceleration of a straight parameter path from the
// centre across the box (the first and second order of their Taylor bounds).
struct PatchBox {
  Vec3 x;
  double ball, speed, half_accel;
};
PatchBox patch_box(const Patch& P, double um, double tm, double du, double dt);

// The nearest point *y of patch Q's surface (arc or segment rotated) to world
// point x, and its distance. The nearest point of a surface of revolution lies
// in x's meridian half-plane: the nearer end point, or the foot on the arc's
// circle (the segment's line) when it falls within the arc (segment).
double patch_nearest(const Patch& Q, const Vec3& x, Vec3* y);

// A pair of points (x on P, y on Q) near a local minimum of their distance,
// from P's parameters `start` (u, th): damped Newton steps on the distance
// from P(u, th) to Q (patch_nearest), its derivatives in closed form (finite
// differences where it has none: at 0, on Q's axis), u kept in [0, 1],
// until a Newton step promises less than `resolution`. Only a
// candidate pair (both points genuine, to rounding): nothing is proven about
// it. Returns their distance.
// each_alone: where a step in both parameters finds no decrease and the
// distance is not convex there (Q's nearest point about to change feature,
// from its face to an end circle), a step in the azimuth alone and one in u
// alone are tried before the descent stops.
double patch_pair_descent(const Patch& P, const Patch& Q, const Vec2& start, double resolution, Vec3* x, Vec3* y,
                          bool each_alone = false);
// The same from the parameters of world point `near` (near P).
double patch_pair_descent(const Patch& P, const Patch& Q, const Vec3& near, double resolution, Vec3* x, Vec3* y);

// The descent's function: the distance from P's point at profile fraction u
// and azimuth th (patch_point) to Q (patch_nearest), with its first and
// second derivatives in (u, th) in closed form; `smooth` is false where they
// do not hold (the distance 0, the point on Q's axis or past P's).
struct PatchPairJet {
  double f = 0, fu = 0, ft = 0, fuu = 0, fut = 0, ftt = 0;
  bool smooth = false;
};
PatchPairJet patch_pair_jet(const Patch& P, const Patch& Q, double u, double th);

// A point of patch P deep on one side of Q's whole surface (the full torus or
// cone it lies on): a damped Newton descent as patch_pair_descent's, but on
// finite differences, of side * g_Q (patch_surface_function, side +1 or -1)
// over P's parameters, from the
// parameters of world point `near`. A candidate for the overlap probes of
// crossing patches (a point of one solid inside the other), not a proof.
Vec3 patch_deep_point(const Patch& P, const Patch& Q, const Vec3& near, double side, double resolution);

// A point where patch P crosses patch Q, from two points of P on either side
// of Q's whole surface (the kernel's a_low and a_high): bisection along the
// segment between their (profile, azimuth) parameters for a zero of Q's
// surface function, accepted when Q's own range holds it. It lies on both
// patches (to rounding): a witness pair of distance ~0 for crossing fits.
bool patch_crossing_point(const Patch& P, const Patch& Q, const Vec3& lo, const Vec3& hi, Vec3* out);

// Lower bound on the distance between two patches from their bounding tori.
double patch_disk_bound(const Patch& A, const Patch& B);

// The cheap first look at a patch pair, enough for most pairs of a query:
// a lower bound (the bounding tori's, and for two toroidal patches also
// dist(major circles) - rho_a - rho_b, since every point of a torus is within
// rho of its major circle) and, when the major circles' closest pair lands
// inside both patches' ranges with the tubes apart, the exact distance (that
// pair's points on the patches attain the bound).
//
// With a goal (the bound that would settle the pair for the caller, and a
// point near where the patches are closest, such as a query's witness), the
// look stops once its bound reaches the goal, and it skips the bounding tori's
// iterative solve when a pair of points of their centre circles (alternating
// projection from the hint) shows that it cannot reach the goal; the closed
// form bound stands in for it. Likewise the major circles' solve, unless that
// pair's tube points come within a chord of both patches (then the major
// circles' closest pair may settle the pair exactly). `complete` says whether
// every solve ran (else lower is weaker than the full look's, below the goal
// all the same).
struct PatchQuick {
  double lower = 0.0;
  bool exact = false;  // then lower is the distance, attained by (x, y)
  bool complete = true;  // no solve skipped for the goal
  Vec3 x = Vec3::Zero(), y = Vec3::Zero();
};
struct QuickGoal {
  double need;  // a lower bound at or above it settles the pair
  Vec3 hint;    // near the patches' closest points
};
PatchQuick patch_pair_quick(const Patch& A, const Patch& B, const QuickGoal* goal = nullptr);


}  // namespace revdist
