// Profile elements, frames and the certified point-in-solid test for the exact
// solid distance (exact/solid_distance_exact.h; SPEC section 2: the solid is the
// region the profile bounds, rotated). Curves come from fit_audit's exact
// Bezier forms, so every piece type is enclosed by one piece of code.
#include <gmpxx.h>

#include <array>
#include <cmath>

#include "core/curve_eval.h"
#include "exact/bezier_ray_crossings.h"
#include "exact/solid_exact_internal.h"

namespace revdist::solid_exact_detail {

namespace {

using fit_audit_detail::curve_part_segments;
using fit_audit_detail::halve;

Poly derivative(const Poly& c) {
  const std::size_t n = c.size() - 1;
  Poly d(n == 0 ? 1 : n);
  for (std::size_t j = 0; j < n; ++j) d[j] = Ia(static_cast<double>(n)) * (c[j + 1] - c[j]);
  return d;
}

P2 seg_point(const HomSeg& s, std::size_t j) { return {s.x[j] / s.w[j], s.y[j] / s.w[j]}; }

// The rotation M(q) / |q|^2 (SPEC section 3) enclosed; exact up to 128-bit rounding.
void rotation(const Pose& p, Ia R[3][3]) {
  const Ia w(p.q[0]), x(p.q[1]), y(p.q[2]), z(p.q[3]);
  const Ia n = w * w + x * x + y * y + z * z;
  const Ia two(2.0);
  R[0][0] = (w * w + x * x - y * y - z * z) / n;
  R[0][1] = two * (x * y - w * z) / n;
  R[0][2] = two * (x * z + w * y) / n;
  R[1][0] = two * (x * y + w * z) / n;
  R[1][1] = (w * w - x * x + y * y - z * z) / n;
  R[1][2] = two * (y * z - w * x) / n;
  R[2][0] = two * (x * z - w * y) / n;
  R[2][1] = two * (y * z + w * x) / n;
  R[2][2] = (w * w - x * x - y * y + z * z) / n;
}

// The axis direction R e3 up to the positive factor |q|^2, exactly.
std::array<mpq_class, 3> axis_exact(const Pose& p) {
  const mpq_class w(p.q[0]), x(p.q[1]), y(p.q[2]), z(p.q[3]);
  return {2 * (x * z + w * y), 2 * (y * z - w * x), w * w - x * x - y * y + z * z};
}

bool parallel(const std::array<mpq_class, 3>& a, const std::array<mpq_class, 3>& b) {
  return a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0];
}

// Crossings of {(r, zeta) : r > rho} with one Bezier segment; -1 when undecided.
int crossings(const HomSeg& s, const Ia& rho, const Ia& zeta, int depth) {
  return exact_detail::bezier_ray_crossings(s.x, s.y, s.w, rho, zeta, 40,
                                            [](const Poly& c, Poly& l, Poly& r) { halve(c, l, r); }, depth);
}

}  // namespace

std::vector<Element> profile_elements(const Profile& profile, std::string* reason) {
  std::vector<Element> out;
  for (std::size_t k = 0; k < profile.pieces.size(); ++k) {
    const Piece& piece = profile.pieces[k];
    const auto [u0, u1] = piece_domain(piece);
    std::vector<HomSeg> segs = curve_part_segments(piece, u0, u1, reason);
    if (segs.empty()) {
      *reason = "piece " + std::to_string(k) + ": " + *reason;
      return {};
    }
    P2 centre;
    bool ccw = true;
    if (piece.kind == PieceKind::arc) {
      // The circumcentre of the three rational points, as fit_audit_curve.cpp does.
      const P2 p0{piece.points[0].x(), piece.points[0].y()};
      const P2 pm{piece.points[1].x(), piece.points[1].y()};
      const P2 p1{piece.points[2].x(), piece.points[2].y()};
      const P2 a = pm - p0, b = p1 - p0;
      const Ia d = Ia(2.0) * fit_audit_detail::cross(a, b);
      const Ia a2 = dot(a, a), b2 = dot(b, b);
      centre = p0 + P2{(b.y * a2 - a.y * b2) / d, (a.x * b2 - b.x * a2) / d};
      ccw = d.pos();
    }
    for (HomSeg& s : segs) {
      Element e;
      e.piece = static_cast<int>(k);
      e.dx = derivative(s.x);
      e.dy = derivative(s.y);
      e.dw = derivative(s.w);
      const std::size_t last = s.w.size() - 1;
      if (piece.kind == PieceKind::arc) {
        e.kind = ElemKind::arc;
        e.c = centre;
        // Arc segments turn at most 1.5 rad and their ends have weight 1.
        e.a = ccw ? seg_point(s, 0) : seg_point(s, last);
        e.b = ccw ? seg_point(s, last) : seg_point(s, 0);
        e.R = hull(fit_audit_detail::norm(e.a - centre), fit_audit_detail::norm(e.b - centre));
      } else if (last == 1) {
        e.kind = ElemKind::line;  // any degree-1 segment is the straight segment between its ends
        e.a = seg_point(s, 0);
        e.b = seg_point(s, 1);
      } else {
        e.kind = ElemKind::curve;
      }
      e.seg = std::move(s);
      out.push_back(std::move(e));
    }
  }
  return out;
}

Frame relative_frame(const Pose& pose_s, const Pose& pose_e) {
  Ia RS[3][3], RE[3][3];
  rotation(pose_s, RS);
  rotation(pose_e, RE);
  Frame f;
  Ia dt[3];
  for (int i = 0; i < 3; ++i) dt[i] = Ia(pose_s.translation[i]) - Ia(pose_e.translation[i]);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) f.M[i][j] = RE[0][i] * RS[0][j] + RE[1][i] * RS[1][j] + RE[2][i] * RS[2][j];
    f.o[i] = RE[0][i] * dt[0] + RE[1][i] * dt[1] + RE[2][i] * dt[2];
  }
  return f;
}

bool exactly_coaxial(const Pose& pose_s, const Pose& pose_e) {
  const auto as = axis_exact(pose_s), ae = axis_exact(pose_e);
  std::array<mpq_class, 3> d;
  for (int i = 0; i < 3; ++i) d[i] = mpq_class(pose_s.translation[i]) - mpq_class(pose_e.translation[i]);
  return parallel(as, ae) && parallel(d, ae);
}

Ia bernstein_eval(const Poly& c, const Ia& u) {
  // b_j + u (b_{j+1} - b_j) rather than (1 - u) b_j + u b_{j+1}: u occurs once per
  // step, so a constant (a polynomial weight 1) stays exact over any interval u.
  Poly b = c;
  for (std::size_t r = 1; r < b.size(); ++r)
    for (std::size_t j = 0; j + r < b.size(); ++j) b[j] = b[j] + u * (b[j + 1] - b[j]);
  return b[0];
}

void elem_point(const Element& e, const Ia& u, Ia& r, Ia& z) {
  const Ia w = bernstein_eval(e.seg.w, u);
  r = bernstein_eval(e.seg.x, u) / w;
  z = bernstein_eval(e.seg.y, u) / w;
}

void elem_point_deriv(const Element& e, const Ia& u, Ia& r, Ia& z, Ia& dr, Ia& dz) {
  const Ia w = bernstein_eval(e.seg.w, u), x = bernstein_eval(e.seg.x, u), y = bernstein_eval(e.seg.y, u);
  const Ia dw = bernstein_eval(e.dw, u), dx = bernstein_eval(e.dx, u), dy = bernstein_eval(e.dy, u);
  r = x / w;
  z = y / w;
  const Ia w2 = sqr(w);
  dr = (dx * w - x * dw) / w2;
  dz = (dy * w - y * dw) / w2;
}

void rotation_cs(double s0, double s1, Ia& c, Ia& sn, Ia* dpsi_ds) {
  const bool second = s0 >= 1.0;  // callers never let a box straddle s = 1
  const double k = second ? 1.0 : 0.0;
  Ia t;
  mpfi_interv_d(t.p(), s0, s1);
  t = Ia(2.0) * (t - Ia(k)) - Ia(1.0);
  const Ia q = Ia(1.0) + sqr(t);
  const Ia two_q = Ia(2.0) / q;
  c = two_q - Ia(1.0);  // t occurs once (in t^2): the exact range
  sn = two_q * t;
  if (second) {
    c = -c;
    sn = -sn;
  }
  if (dpsi_ds) *dpsi_ds = Ia(2.0) * two_q;
}

double psi_of(double s) {
  const bool second = s >= 1.0;
  const double t = 2.0 * (s - (second ? 1.0 : 0.0)) - 1.0;
  return 2.0 * std::atan(t) + (second ? M_PI : 0.0);
}

void surface_point(const Element& s_elem, const Frame& f, const Ia& u, double s, Ia y[3]) {
  Ia r, z;
  elem_point(s_elem, u, r, z);
  Ia c, sn;
  rotation_cs(s, s, c, sn);
  for (int k = 0; k < 3; ++k) y[k] = f.o[k] + r * (c * f.M[k][0] + sn * f.M[k][1]) + z * f.M[k][2];
}

Inside point_in_solid(const std::vector<Element>& elems, const Ia& rho, const Ia& zeta) {
  int total = 0;
  for (const Element& e : elems) {
    const int n = crossings(e.seg, rho, zeta, 0);
    if (n < 0) return Inside::unknown;
    total += n;
  }
  return total % 2 == 1 ? Inside::inside : Inside::outside;
}

}  // namespace revdist::solid_exact_detail
