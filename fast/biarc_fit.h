// G1 biarc of a spiral and its proven error: the lens bound (paper section 4.1,
// NOTES section 3).
//
// Chord frame: v = p1 - p0, d = |v|, alpha = angle(v, t0), beta = angle(v, t1)
// (signed). L_A is the circle arc through p0, p1 tangent to t0 at p0 (its
// height over the chord peaks at (d/2) tan(alpha/2)); L_B the arc tangent to t1
// at p1 (peak (d/2) tan(-beta/2)). The lens is the region between them.
//
// Theorem (Vogt 1931; Kurnosenko, "Biarcs and bilens", CAGD 2013): a spiral
// arc - continuous curvature of one sign, monotone, tangent turning < pi -
// lies in its lens. Hypotheses here: the spiral split (fast/spiral_split.h)
// makes r', z', K and N sign-constant on the span, so the curvature is monotone
// with one sign and the tangent stays in one closed quadrant (turning <= 90
// degrees, hence |alpha|, |beta| <= 90 degrees).
//
// Lemma 1 (biarc in the lens): every biarc with the data has its joint J on the
// joint circle (tangent at p0 at the mean angle (alpha - beta)/2), whose arc
// between p0 and p1 lies between L_A and L_B. If J is on that arc, the first
// arc (a circle tangent to L_A at p0, through J inside the lens) cannot leave
// the lens: it meets L_A only at p0 (tangent circles) and L_B at most once
// besides p0, so leaving and re-entering is impossible. Same for the second arc.
// We always put J on the joint arc (the curve's crossing, projected on it).
//
// Lemma 2 (width): with |alpha|, |beta| <= 90 degrees both lens arcs are graphs
// over the chord, and their height difference is largest at the chord midpoint
// (d/dR of sqrt(R^2 - t^2) - sqrt(R^2 - d^2/4) is largest in size at t = 0).
// Both the spiral and the biarc join p0 to p1 inside the lens, so each crosses
// every chord-normal section of it; a point of one is therefore within the
// section length of a point of the other. Hence the two-sided Hausdorff
// distance is at most
//     W = (d/2) |tan(alpha/2) + tan(beta/2)|     (= O(h^3) for a span of length h).
// The same containment gives the node's segment bound: the curve's height over
// the chord lies in [min(0, sA, sB), max(0, sA, sB)] and its projection on the
// chord stays in [0, d] (tangent angles between alpha and beta, both <= 90
// degrees), so the chord shifted to the middle of that band is within half its
// width of every point of the curve and the biarc.
#pragma once
#include "core/arc2.h"
#include "core/vec.h"
#include "fast/spiral_split.h"

namespace revdist {

// The lens of Hermite data and what it proves.
struct LensBound {
  double width = 0.0;     // W above: the two-sided Hausdorff bound (before rounding slack)
  double alpha = 0.0, beta = 0.0;
  // |alpha|, |beta| <= 90 degrees (+ rounding) and Vogt's inequality agrees with
  // the end curvatures (|kappa| grows <=> |angle| grows). False means the span
  // is not a spiral as required; W then proves nothing.
  bool hypotheses_ok = true;
};
LensBound lens_bound(const SpanEnds& ends);

struct Biarc {
  Arc2 arc[2];
};

// The arc from p with unit tangent t to q (straight when q - p is along t).
Arc2 arc_from_tangent(const Vec2& p, const Vec2& t, const Vec2& q);

// The point of the joint arc (the joint circle between p0 and p1, a graph over
// the chord) above or below `hint`'s chord coordinate (clamped to the chord).
// Computed in the chord frame with y = x (d - x) k / (sqrt(1 - k^2 m^2) + cos),
// which has no cancellation as the joint circle flattens (k -> 0).
Vec2 joint_on_circle(const SpanEnds& ends, const Vec2& hint);

// The biarc through the joint J (on the joint circle): first arc from p0
// tangent to t0 to J, second from J, tangent-continuous, to p1.
Biarc biarc_with_joint(const SpanEnds& ends, const Vec2& joint);

// The biarc of the curve part piece[u0, u1] with end data `ends`. Joint rule:
// the curve's own crossing of the joint circle (Newton on g(C(u)) from the mid
// parameter, whose point `mid` the caller has already evaluated), projected
// on the joint arc. The proven bound W does not depend on the joint (lemma 1
// holds for any J on the joint arc), but the true error does: NOTES section 3
// measured this rule near-optimal and never breaking the biarc's curvature
// monotonicity, unlike the equal-chord joint. Tighter fits make the distance
// brackets tighter.
Biarc fit_curve_biarc(const Piece& piece, double u0, double u1, const SpanEnds& ends, const Vec2& mid);

// A segment (a truncated cone when rotated) and a radius such that every point
// of the spiral and of any biarc in its lens is within `radius` of the segment.
struct Capsule {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  double radius = 0.0;
};
Capsule lens_capsule(const SpanEnds& ends, const LensBound& lens);

// The smallest capsule along the principal axis of two capsules' segment end
// points that contains both (distance to a segment is convex, so the end points
// of each child segment are the worst points).
Capsule capsule_union(const Capsule& c0, const Capsule& c1);

}  // namespace revdist
