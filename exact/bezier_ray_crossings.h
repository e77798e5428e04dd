// The crossing count of the ray {(r, zeta) : r > rho} with one rational Bezier
// segment in homogeneous Bernstein form, for the point-in-solid tests of
// exact/ (on MPFI intervals and on outward-rounded doubles alike).
#pragma once
#include <cstddef>
#include <vector>

namespace revdist::exact_detail {

// Crossings of {(r, zeta) : r > rho} with the segment (x, y, w) (w x, w y, w;
// the weights' enclosures positive); -1 when undecided within max_depth
// halvings. I has pos() / neg() (every point of the enclosure > 0 / < 0);
// halve(c, left, right) is de Casteljau at t = 1/2 (exact in binary).
template <class I, class Halve>
int bezier_ray_crossings(const std::vector<I>& x, const std::vector<I>& y, const std::vector<I>& w, const I& rho,
                         const I& zeta, int max_depth, const Halve& halve, int depth = 0) {
  const std::size_t n = w.size();
  std::vector<I> Z(n), Rr(n);
  bool zpos = true, zneg = true, rneg = true, rpos = true;
  for (std::size_t j = 0; j < n; ++j) {
    Z[j] = y[j] - zeta * w[j];
    Rr[j] = x[j] - rho * w[j];
    zpos = zpos && Z[j].pos();
    zneg = zneg && Z[j].neg();
    rneg = rneg && Rr[j].neg();
    rpos = rpos && Rr[j].pos();
  }
  if (zpos || zneg || rneg) return 0;  // convex hull off the ray's line / left of the point
  if (rpos) {
    // Bernstein form of Z with strict signs: sign variations bound the roots in
    // (0, 1) and have their parity, so one variation is exactly one crossing.
    bool strict = true;
    int variations = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (!Z[j].pos() && !Z[j].neg()) strict = false;
      if (j > 0 && Z[j].pos() != Z[j - 1].pos()) ++variations;
    }
    if (strict && variations == 1) return 1;
  }
  if (depth >= max_depth) return -1;
  std::vector<I> lx, rx, ly, ry, lw, rw;
  halve(x, lx, rx);
  halve(y, ly, ry);
  halve(w, lw, rw);
  const int a = bezier_ray_crossings(lx, ly, lw, rho, zeta, max_depth, halve, depth + 1);
  if (a < 0) return -1;
  const int b = bezier_ray_crossings(rx, ry, rw, rho, zeta, max_depth, halve, depth + 1);
  return b < 0 ? -1 : a + b;
}

}  // namespace revdist::exact_detail
