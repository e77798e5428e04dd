// Evaluation of profile pieces in the meridian plane (r, z): points and up to
// third derivatives, the quantities the spiral split of paper section 4.1 needs.
#pragma once
#include <utility>
#include <vector>

#include "core/profile.h"
#include "core/vec.h"

namespace revdist {

// Parameter domain: [knots.front(), knots.back()] for bspline, [0, 1] for line, arc, bezier.
std::pair<double, double> piece_domain(const Piece& piece);

// out[0] = C(u), out[k] = k-th derivative of C at u, for k = 1..n (n <= 3). Rational (weighted) pieces handled
// by the quotient rule on homogeneous coordinates. Arcs are parametrised uniformly in angle (constant speed),
// lines linearly. B-splines: at a knot, derivatives are those of the span starting at u (right limit), except at the end.
// u outside the domain is clamped to it. At either end of the domain out[0] is exactly the end
// control point (every piece interpolates its ends), so pieces that join exactly still join.
// `out` must hold n + 1 entries.
void piece_derivatives(const Piece& piece, double u, int n, Vec2* out);

Vec2 piece_point(const Piece& piece, double u);

// For an arc piece: centre, radius, start angle and signed sweep (|sweep| < 2*pi) from its three points;
// collinear points are an error the reader reports.
// Precondition: the three points are not collinear (read_case rejects such arcs); for
// collinear points the result has an infinite or NaN radius.
// The sweep is positive when p0 -> pm -> p1 turns counter-clockwise in (r, z).
struct ArcGeometry { Vec2 center; double radius; double start_angle; double sweep; };
ArcGeometry arc_geometry(const Piece& arc);

// A piece as consecutive rational Bezier segments with positive weights (empty weights:
// polynomial), the form in which convex-hull and Descartes (sign-change) arguments apply.
// Segment k covers [u0, u1] of the piece's domain; consecutive segments share end points
// exactly. bspline: one segment per non-empty knot span (knot insertion by blossoming);
// bezier and line: the piece itself; arc: rational quadratics of at most 90 degrees each,
// whose parametrisation differs from the arc's uniform angle (the geometry is the same).
struct BezierSegment {
  std::vector<Vec2> points;
  std::vector<double> weights;
  double u0 = 0.0, u1 = 1.0;
  int degree() const { return static_cast<int>(points.size()) - 1; }
};
std::vector<BezierSegment> piece_bezier_segments(const Piece& piece);

// Splits a segment at local parameter t in (0, 1) by de Casteljau on homogeneous points;
// the two halves share the split point exactly. u0/u1 are interpolated linearly, which is
// exact for polynomial and rational Bezier segments of bezier and bspline pieces.
std::pair<BezierSegment, BezierSegment> split_segment(const BezierSegment& s, double t);

// The largest distance of control points from the chord of the first and last
// (the segment between them). A rational Bezier segment with positive weights
// lies in the hull of its control points, so within this of its chord; so do
// consecutive segments whose control points are listed together. And since
// the curve runs from one chord end to the other inside that band, every chord
// point is within it of the curve too (a Hausdorff bound).
double chord_flatness(const std::vector<Vec2>& points);

}  // namespace revdist
