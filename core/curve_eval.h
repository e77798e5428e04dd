// Evaluation of profile pieces in the meridian plane (r, z): points and up to
// third derivatives, the quantities the spiral split of paper section 4.1 needs.
#pragma once
#include <utility>

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

}  // namespace revdist
