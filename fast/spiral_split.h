// Splitting a profile into spirals (paper section 4.1): parameter spans on which
// r and z are monotone, the curvature has one sign and is monotone, and the
// speed does not vanish. These are the hypotheses of the lens bound that
// fast/biarc_fit.h relies on.
#pragma once
#include <cstdint>
#include <vector>

#include "core/profile.h"
#include "core/vec.h"

namespace revdist {

enum class SpanKind : std::uint8_t {
  line,   // an input line piece: represented exactly by one straight Arc2
  arc,    // part of an input arc piece: represented exactly by Arc2s
  curve,  // part of a Bezier / B-spline piece: approximated by biarcs
};

// Hermite data of a curve part: end points and unit tangents (limits taken from
// inside the part, so a corner or a cusp at an end does not matter) and the
// signed curvatures there (0 for lines; only a sanity check of the hypotheses).
struct SpanEnds {
  Vec2 p0 = Vec2::Zero(), t0 = Vec2(1, 0);
  Vec2 p1 = Vec2::Zero(), t1 = Vec2(1, 0);
  double k0 = 0.0, k1 = 0.0;
};

// One spiral: the parameter range [u0, u1] of profile piece `piece`
// (parameters as in core/curve_eval.h, so an audit can re-evaluate it).
struct SpiralSpan {
  std::int32_t piece = 0;
  SpanKind kind = SpanKind::curve;
  double u0 = 0.0, u1 = 0.0;
  SpanEnds ends;
  // The isolation of the split points finished within its work bound, so r',
  // z', K and N are proven to keep one sign on the span (to within a few ulp
  // of the parameter at its ends). Always true for lines and arcs.
  bool proven = true;
};

// Appends the spirals of every piece of `profile`, in chain order, to `out`
// (which is cleared first; its capacity is reused, so rebuilding a deformable
// solid does not allocate once warmed up).
//
// Split points of a Bezier / B-spline piece: the sign changes of r', z', of
// K = r'z'' - r''z' (inflections) and of N = |C'|^5 dkappa/du (curvature
// extrema), the points where the speed is zero to within rounding (singular
// points), and the interior knots where the curve is not C2 (its curvature may
// jump there). The sign changes are isolated with proof on the polynomial
// numerators of each Bezier segment (homogeneous form for rational ones; see
// fast/bernstein.h): every sign change is found, and a root of even
// multiplicity (no sign change) is not split at. A line piece is one span; an arc piece is split
// at its r and z extremes so that each span turns by at most 90 degrees.
// Zero-length pieces contribute nothing.
void split_into_spirals(const Profile& profile, std::vector<SpiralSpan>& out);

// Unit tangent of `piece` at u as the limit from the side `side` (+1: from
// above, for a span starting at u; -1: from below, for a span ending at u),
// and the signed curvature there. At a singular point (C'(u) = 0) the tangent
// is the direction of the first non-vanishing derivative, signed for the side.
// Returns the point C(u).
Vec2 piece_tangent(const Piece& piece, double u, int side, Vec2* unit_tangent, double* curvature);

}  // namespace revdist
