// Ray parity of a point against a sampled profile: the inside test of the
// brute-force references (compare/brute_force, tests/fast/solid_test_util.h).
#pragma once
#include <cstddef>
#include <vector>

#include "core/vec.h"

namespace revdist {

// Crossings of the ray {(r, q.z) : r > q.r} with the polyline through pts
// (half-open in z), where consecutive samples of one piece (piece[i] equal)
// are joined and a new piece starts at its predecessor's end point. Odd: q is
// inside. Right for the true curve when q is farther from it than the
// polyline's chordal error.
inline bool polyline_inside(const std::vector<Vec2>& pts, const std::vector<int>& piece, const Vec2& q) {
  int crossings = 0;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    if (piece[i] != piece[i + 1]) continue;  // the next piece starts at the same point
    const Vec2 p = pts[i], r = pts[i + 1];
    if ((p.y() <= q.y()) == (r.y() <= q.y())) continue;
    const double x = p.x() + (q.y() - p.y()) * (r.x() - p.x()) / (r.y() - p.y());
    if (x > q.x()) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace revdist
