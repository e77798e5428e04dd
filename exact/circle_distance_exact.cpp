// Certified circle-circle distance (paper §3.2 and Appendix A, done exactly).
// Named cases first (points, coaxial, contact), then the binormal polynomial
// H(x) of degree <= 8 isolated with CGAL, and the distance at every candidate
// enclosed with MPFI. The lower bound is the smallest enclosure over all
// candidates (the minimiser is one of them); the upper bound only ever comes
// from genuine points of circle b.
#include "exact/circle_distance_exact.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>

#include "exact/circle_exact_internal.h"
#include "exact/circle_interval.h"

namespace revdist {
namespace {

using namespace exact_detail;

// Phase timings on stderr when built with -DREVDIST_EXACT_PROFILE (how the
// filters below were chosen); compiled out otherwise.
#ifdef REVDIST_EXACT_PROFILE
struct Prof { const char* name; double ms = 0; ~Prof() { std::fprintf(stderr, "%s %.1f ms\n", name, ms); } };
struct ProfScope { Prof& p; std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  ~ProfScope() { p.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(); } };
#define PROF(name) static Prof prof_##name{#name}; ProfScope prof_scope_##name{prof_##name}
#else
#define PROF(name)
#endif

constexpr int kGuardBits = 32;   // extra MPFI bits over the x-approximation
constexpr int kStartBits = 112;  // first attempt: enough for 1e-30 on benign inputs

// ------------------------------------------------------------ enclosures

Iv q_iv(mpfr_prec_t p, const mpq_class& q) { return Iv(p, q); }

// Δ = P − C_a for P = C_b + x u + y v.
std::array<Iv, 3> delta_of(const PairFrame& f, const Iv& x, const Iv& y) {
  const mpfr_prec_t p = x.prec();
  return {q_iv(p, f.D[0]) + x * q_iv(p, f.u[0]) + y * q_iv(p, f.v[0]),
          q_iv(p, f.D[1]) + x * q_iv(p, f.u[1]) + y * q_iv(p, f.v[1]),
          q_iv(p, f.D[2]) + x * q_iv(p, f.u[2]) + y * q_iv(p, f.v[2])};
}

// dist(P, a) = hypot(h, ρ − R) with ρ − R = (ρ² − R²)/(ρ + R): no cancellation
// beyond the one in ρ² − R², so the width stays ~2^-p·scale even at contact.
Iv dist_enclosure(const PairFrame& f, const std::array<Iv, 3>& d) {
  const mpfr_prec_t p = d[0].prec();
  const Iv n0 = q_iv(p, f.n[0]), n1 = q_iv(p, f.n[1]), n2c = q_iv(p, f.n[2]);
  const Iv hn = n0 * d[0] + n1 * d[1] + n2c * d[2];
  const Iv c0 = n1 * d[2] - n2c * d[1], c1 = n2c * d[0] - n0 * d[2], c2 = n0 * d[1] - n1 * d[0];
  const Iv nn = q_iv(p, f.n2);
  const Iv rho2 = (sqr(c0) + sqr(c1) + sqr(c2)) / nn;
  const Iv h = hn / sqrt_nonneg(nn);
  const Iv rho = sqrt_nonneg(rho2);
  if (sgn(f.Ra) == 0) return hypot(h, rho);
  const Iv ra = q_iv(p, f.Ra);
  return hypot(h, (rho2 - q_iv(p, f.Ra2)) / (rho + ra));
}

Iv iv_of_interval(mpfr_prec_t p, const mpq_class& lo, const mpq_class& hi) {
  Iv r(p);
  mpfi_interv_q(r.get(), lo.get_mpq_t(), hi.get_mpq_t());
  return r;
}

Iv y_of(const PairFrame& f, const Iv& x, int sigma) {
  Iv y(x.prec());
  if (sigma == 0) {
    mpfi_set_si(y.get(), 0);
    return y;
  }
  const Iv s = q_iv(x.prec(), f.s.c[0]) + q_iv(x.prec(), f.s.c[2]) * sqr(x);
  y = sqrt_nonneg(s);
  return sigma < 0 ? neg(y) : y;
}

Vec3 mid_vec(const std::array<Iv, 3>& v) {
  Vec3 r;
  mpfr_t m;
  mpfr_init2(m, v[0].prec());
  for (int i = 0; i < 3; ++i) {
    mpfi_mid(m, v[i].get());
    r[i] = mpfr_get_d(m, MPFR_RNDN);
  }
  mpfr_clear(m);
  return r;
}

// Some point of a, for when every point of a is a closest point.
Vec3 any_point_on_a(const Circle3& a) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(a.normal[i]) < std::abs(a.normal[k])) k = i;
  const Vec3 w = Vec3::Unit(k).cross(a.normal).normalized();
  return a.center + a.radius * w;
}

// The near point of a to P (Δ = P − C_a), rounded to double.
Vec3 near_point_on_a(const PairFrame& f, const Circle3& a, const std::array<Iv, 3>& d) {
  const mpfr_prec_t p = d[0].prec();
  if (sgn(f.Ra) == 0) return a.center;
  const Iv hn = q_iv(p, f.n[0]) * d[0] + q_iv(p, f.n[1]) * d[1] + q_iv(p, f.n[2]) * d[2];
  const Iv k = hn / q_iv(p, f.n2);
  std::array<Iv, 3> perp = {d[0] - k * q_iv(p, f.n[0]), d[1] - k * q_iv(p, f.n[1]),
                            d[2] - k * q_iv(p, f.n[2])};
  const Iv len = sqrt_nonneg(sqr(perp[0]) + sqr(perp[1]) + sqr(perp[2]));
  if (mpfi_has_zero(len.get())) return any_point_on_a(a);
  const Iv scale = q_iv(p, f.Ra) / len;
  std::array<Iv, 3> q = {q_iv(p, f.ca[0]) + scale * perp[0], q_iv(p, f.ca[1]) + scale * perp[1],
                         q_iv(p, f.ca[2]) + scale * perp[2]};
  return mid_vec(q);
}

// ------------------------------------------------------------ result helpers

std::string decimal_in(mpfr_srcptr lo, mpfr_srcptr hi) {
  if (mpfr_zero_p(lo) && mpfr_zero_p(hi)) return "0";
  const mpfr_prec_t p = std::max(mpfr_get_prec(lo), mpfr_get_prec(hi)) + 2;
  mpfr_t mid, rd, ru;
  mpfr_inits2(p, mid, static_cast<mpfr_ptr>(nullptr));
  mpfr_add(mid, lo, hi, MPFR_RNDN);  // exact at p bits
  mpfr_div_2ui(mid, mid, 1, MPFR_RNDN);
  std::string out;
  for (int digits = 40; digits <= 1200 && out.empty(); digits += 40) {
    char* s = nullptr;
    mpfr_asprintf(&s, "%.*Re", digits - 1, mid);
    // Read the decimal back with outward rounding; keep it only if provably inside.
    const mpfr_prec_t rp = 4 * digits + p + 64;
    mpfr_init2(rd, rp);
    mpfr_init2(ru, rp);
    mpfr_set_str(rd, s, 10, MPFR_RNDD);
    mpfr_set_str(ru, s, 10, MPFR_RNDU);
    if (mpfr_cmp(rd, lo) >= 0 && mpfr_cmp(ru, hi) <= 0) out = s;
    mpfr_clear(rd);
    mpfr_clear(ru);
    mpfr_free_str(s);
  }
  mpfr_clear(mid);
  return out;
}

void set_interval(ExactCircleResult& r, mpfr_srcptr lo, mpfr_srcptr hi) {
  r.lower = mpfr_get_d(lo, MPFR_RNDD);
  r.upper = mpfr_get_d(hi, MPFR_RNDU);
  {
    mpfr_t w;
    mpfr_init2(w, 64);
    mpfr_sub(w, hi, lo, MPFR_RNDU);
    r.width = mpfr_get_d(w, MPFR_RNDU);
    mpfr_clear(w);
  }
  r.decimal = decimal_in(lo, hi);
  mpfr_t mid;
  mpfr_init2(mid, std::max(mpfr_get_prec(lo), mpfr_get_prec(hi)) + 2);
  mpfr_add(mid, lo, hi, MPFR_RNDN);
  mpfr_div_2ui(mid, mid, 1, MPFR_RNDN);
  r.distance = mpfr_get_d(mid, MPFR_RNDN);
  mpfr_clear(mid);
}

void set_contact(ExactCircleResult& r, const Vec3& p) {
  r.contact = true;
  r.lower = r.upper = r.distance = r.width = 0.0;
  r.decimal = "0";
  r.point_a = r.point_b = p;
}

ExactCircleResult not_certified(std::string why) {
  ExactCircleResult r;
  r.status = ExactStatus::not_certified;
  r.reason = std::move(why);
  r.lower = 0.0;
  r.upper = HUGE_VAL;
  r.width = HUGE_VAL;
  r.distance = NAN;
  return r;
}

bool is_finite(const Circle3& c) {
  return c.center.allFinite() && c.normal.allFinite() && std::isfinite(c.radius);
}

// An interval [lo, hi] of width w is narrow enough when w <= target (relative
// to the pair's scale) and its middle is the nearest double of every point of
// it: lo and hi round to the same double, or, straddling a tie between two,
// w is within 2^-80 of lo (the middle is then a nearest double up to 2^-28
// ulp). A distance far below the scale (radii 1e50, distance 1) needs that
// many more bits than the target alone: at the target alone the interval
// [0, 9.9e13] was "ok" for a distance of 1.
bool narrow_enough(mpfr_srcptr lo, mpfr_srcptr hi, mpfr_srcptr w, double target) {
  if (!mpfr_number_p(w) || mpfr_cmp_d(w, target) > 0) return false;
  if (mpfr_get_d(lo, MPFR_RNDN) == mpfr_get_d(hi, MPFR_RNDN)) return true;
  Fr tie(64);
  mpfr_mul_2si(tie.get(), lo, -80, MPFR_RNDD);
  return mpfr_cmp(w, tie.get()) <= 0;
}

// Encloses a closed form at increasing precision until it is narrow enough.
template <class F>
bool enclose_closed_form(F&& eval, double target, int max_bits, ExactCircleResult& r) {
  for (int bits = kStartBits; bits <= max_bits; bits *= 2) {
    const Iv d = eval(static_cast<mpfr_prec_t>(bits + kGuardBits));
    Fr lo(d.prec()), hi(d.prec());
    mpfi_get_left(lo.get(), d.get());
    mpfi_get_right(hi.get(), d.get());
    if (mpfr_sgn(lo.get()) < 0) mpfr_set_zero(lo.get(), 1);
    Fr w(d.prec());
    mpfr_sub(w.get(), hi.get(), lo.get(), MPFR_RNDU);
    const bool narrow = narrow_enough(lo.get(), hi.get(), w.get(), target);
    if (narrow || 2 * bits > max_bits) {
      set_interval(r, lo.get(), hi.get());
      if (!narrow) {
        r.status = ExactStatus::not_certified;
        r.reason = "closed form: width target not reached at max_precision_bits";
      }
      return true;
    }
  }
  return false;
}

// ------------------------------------------------------------ named cases

ExactCircleResult point_point(const Circle3& a, const Circle3& b, double target, int max_bits) {
  ExactCircleResult r;
  r.point_a = a.center;
  r.point_b = b.center;
  mpq_class d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const mpq_class d = mpq_class(b.center[i]) - mpq_class(a.center[i]);
    d2 += d * d;
  }
  if (sgn(d2) == 0) {
    set_contact(r, a.center);
    return r;
  }
  r.binormals = 1;
  enclose_closed_form([&](mpfr_prec_t p) { return sqrt_nonneg(Iv(p, d2)); }, target, max_bits, r);
  return r;
}

// b is a point, a a circle of positive radius: √(h² + (ρ − R)²).
ExactCircleResult point_circle(const Circle3& a, const Circle3& b, double target, int max_bits) {
  ExactCircleResult r;
  const PairFrame f = make_frame(a, b);
  r.point_b = b.center;
  const mpq_class rho2num = f.rho2num.c[0][0], hnum = f.hnum.c[0][0];
  const bool on_axis = sgn(rho2num) == 0;
  // Lines: to the near and the far point of a, only the far one when b lies on
  // a (the near one has length 0), a cone of them from a's axis.
  r.binormals = on_axis ? -1 : 2;
  {
    const mpfr_prec_t p = 128;
    const Iv zero(p, mpq_class(0));
    r.point_a = near_point_on_a(f, a, delta_of(f, zero, zero));
  }
  if (sgn(hnum) == 0 && rho2num == f.Ra2 * f.n2) {
    set_contact(r, b.center);
    r.binormals = 1;
    return r;
  }
  if (on_axis) r.status = ExactStatus::infinitely_many;
  enclose_closed_form(
      [&](mpfr_prec_t p) {
        const Iv zero(p, mpq_class(0));
        return dist_enclosure(f, delta_of(f, zero, zero));
      },
      target, max_bits, r);
  return r;
}

void swap_sides(ExactCircleResult& r) { std::swap(r.point_a, r.point_b); }

// ------------------------------------------------------------ filtered signs

int xshift_for(const PairFrame& f) {
  // x ranges over ±r_b/|u|; approximate it to bits relative to that range.
  const double xr = f.rb.get_d() / std::sqrt(f.alpha.get_d());
  int e = 0;
  std::frexp(xr, &e);
  return -e;
}

Iv eval_bipoly(const BiPoly& p, const Iv& X, const Iv& Y) {
  const mpfr_prec_t pr = X.prec();
  Iv acc(pr, mpq_class(0));
  for (int j = kMaxDeg; j >= 0; --j) {
    Iv row(pr, mpq_class(0));
    for (int i = kMaxDeg - j; i >= 0; --i) row = row * X + Iv(pr, p.c[i][j]);
    acc = acc * Y + row;
  }
  return acc;
}

int iv_sign(const Iv& v) {
  if (mpfi_is_strictly_pos(v.get())) return 1;
  if (mpfi_is_strictly_neg(v.get())) return -1;
  return 0;  // undecided
}

// An enclosure of a real algebraic number of absolute width <= 2^-abs_bits:
// interval Newton on its square-free defining polynomial inside CGAL's
// isolating interval (quadratic, where CGAL's own refinement bisects), with
// bisection while p' may vanish and CGAL's refinement as the last resort.
Iv x_enclosure(const Real1& x, int abs_bits) {
  static const AK ak;
  const mpfr_prec_t prec = std::max(abs_bits, 0) + 64;
  if (x.is_rational()) return Iv(prec, mpq_class(x.rational().mpq()));
  const Poly1Z& poly = x.polynomial();
  const int deg = poly.degree();
  std::vector<mpz_class> pc(deg + 1), dc(deg);
  for (int i = 0; i <= deg; ++i) pc[i] = mpz_class(poly[i].mpz());
  for (int i = 1; i <= deg; ++i) dc[i - 1] = pc[i] * i;
  auto eval_z = [prec](const std::vector<mpz_class>& c, const Iv& X) {
    Iv acc(prec);
    mpfi_set_si(acc.get(), 0);
    for (int i = static_cast<int>(c.size()) - 1; i >= 0; --i) {
      acc = acc * X;
      mpfi_add_z(acc.get(), acc.get(), c[i].get_mpz_t());
    }
    return acc;
  };
  Iv X = iv_of_interval(prec, mpq_class(x.low().mpq()), mpq_class(x.high().mpq()));
  mpfr_t d, m;
  mpfr_init2(d, 64);
  mpfr_init2(m, prec);
  bool done = false;
  for (int iter = 0; iter < 4 * abs_bits + 64; ++iter) {
    mpfi_diam_abs(d, X.get());
    if (mpfr_cmp_si_2exp(d, 1, -abs_bits) <= 0) {
      done = true;
      break;
    }
    mpfi_mid(m, X.get());
    Iv M(prec);
    mpfi_set_fr(M.get(), m);
    const Iv PM = eval_z(pc, M);
    const Iv DX = eval_z(dc, X);
    if (!mpfi_has_zero(DX.get())) {
      const Iv N = M - PM / DX;
      Iv Xn(prec);
      mpfi_intersect(Xn.get(), X.get(), N.get());
      if (mpfi_is_empty(Xn.get())) break;
      mpfr_t dn;
      mpfr_init2(dn, 64);
      mpfi_diam_abs(dn, Xn.get());
      mpfr_mul_2si(dn, dn, 1, MPFR_RNDU);
      const bool halved = mpfr_cmp(dn, d) <= 0;
      mpfr_clear(dn);
      X = Xn;
      if (halved) continue;
    }
    // Bisection on the sign of p at the midpoint against the left end.
    Iv Lx(prec);
    mpfi_set_fr(Lx.get(), &X.get()->left);
    const int sl = iv_sign(eval_z(pc, Lx)), sm = iv_sign(PM);
    if (sl == 0 || sm == 0) break;
    Iv half(prec);
    if (sl == sm)
      mpfi_interv_fr(half.get(), m, &X.get()->right);
    else
      mpfi_interv_fr(half.get(), &X.get()->left, m);
    X = half;
  }
  mpfr_clear(d);
  mpfr_clear(m);
  if (done) return X;
  const auto ab = ak.approximate_absolute_1_object()(x, abs_bits);
  return iv_of_interval(prec, mpq_class(ab.first.mpq()), mpq_class(ab.second.mpq()));
}

// A BiPoly with its coefficients converted to intervals once.
class IvBiPoly {
 public:
  IvBiPoly(const BiPoly& p, mpfr_prec_t prec) {
    for (int i = 0; i <= kMaxDeg; ++i)
      for (int j = 0; i + j <= kMaxDeg; ++j) {
        c_.emplace_back(prec, p.c[i][j]);
        idx_[i][j] = static_cast<int>(c_.size()) - 1;
      }
  }
  Iv eval(const Iv& X, const Iv& Y) const {
    const mpfr_prec_t pr = X.prec();
    Iv acc(pr, mpq_class(0));
    for (int j = kMaxDeg; j >= 0; --j) {
      Iv row(pr, mpq_class(0));
      for (int i = kMaxDeg - j; i >= 0; --i) row = row * X + c_[idx_[i][j]];
      acc = acc * Y + row;
    }
    return acc;
  }

 private:
  std::vector<Iv> c_;
  int idx_[kMaxDeg + 1][kMaxDeg + 1] = {};
};

Iv s_of(const PairFrame& f, const Iv& X) {
  const mpfr_prec_t p = X.prec();
  return Iv(p, f.s.c[0]) + Iv(p, f.s.c[2]) * sqr(X);
}

struct Box {
  Iv X, Y;
};

// An interval box around a point of b, x to about 2^-bits of its range.
Box box_of(const PairFrame& f, const PointB& pt, int bits, int xshift) {
  Iv X = x_enclosure(pt.x, bits + xshift);
  Iv Y = y_of(f, X, pt.sigma);
  return {X, Y};
}

// Sign of p at a point of b: intervals first, the exact test only on a tie.
int sign_filtered(const PairFrame& f, const BiPoly& p, const PointB& pt, int xshift) {
  for (int bits : {64, 192}) {
    const Box b = box_of(f, pt, bits, xshift);
    if (const int sg = iv_sign(eval_bipoly(p, b.X, b.Y))) return sg;
  }
  PROF(exact_sign);
  return sign_on_b(f, p, pt);
}

int sign_s_filtered(const PairFrame& f, const Real1& x, int xshift) {
  for (int bits : {64, 192}) {
    const Iv X = x_enclosure(x, bits + xshift);
    const mpfr_prec_t p = X.prec();
    if (const int sg = iv_sign(Iv(p, f.s.c[0]) + Iv(p, f.s.c[2]) * sqr(X))) return sg;
  }
  PROF(exact_s);
  return sign_of_s(f, x);
}

// ------------------------------------------------------------ candidates

struct Candidate {
  PointB pt;
  bool continuum = false;  // every point of a is closest (axis crossing), or f constant nearby
  Fr lo, hi;               // enclosure lower end; upper end at a genuine point (inf if none)
  mpq_class xt;            // the genuine point used for hi
  int st = 1;
  bool evaluated = false;
};

// Encloses the distance at a candidate with the root approximated to 2^-(bits+xshift).
void evaluate(const PairFrame& f, Candidate& c, int bits, int xshift) {
  PROF(evaluate);
  const Iv X = x_enclosure(c.pt.x, bits + xshift);
  const mpfr_prec_t p = X.prec();
  mpq_class xl, xu;
  mpfr_get_q(xl.get_mpq_t(), &X.get()->left);
  mpfr_get_q(xu.get_mpq_t(), &X.get()->right);
  const Iv d = dist_enclosure(f, delta_of(f, X, y_of(f, X, c.pt.sigma)));
  c.lo = Fr(p);
  mpfi_get_left(c.lo.get(), d.get());
  if (mpfr_sgn(c.lo.get()) < 0) mpfr_set_zero(c.lo.get(), 1);
  c.hi = Fr(p);  // +inf
  const mpq_class tries[3] = {(xl + xu) / 2, xl, xu};
  for (const mpq_class& xt : tries) {
    if (sgn(eval(f.s, xt)) < 0) continue;  // not a point of b
    const Iv Xt(p, xt);
    const int st = c.pt.sigma == 0 ? 1 : c.pt.sigma;
    const Iv dt = dist_enclosure(f, delta_of(f, Xt, y_of(f, Xt, st)));
    mpfi_get_right(c.hi.get(), dt.get());
    c.xt = xt;
    c.st = st;
    break;
  }
  c.evaluated = true;
}

struct CandidateSet {
  std::vector<Candidate> list;
  int binormals = 0;
  bool h_zero = false;
};

// The binormal lines that leave the point p of b where G = 0 (README,
// `circles`: the same count as fast/). On a's axis: those in the plane normal
// to b at p, two, or one where that plane is tangent to a (axis_test = 0). At a
// contact point only the far line, if the far branch is critical there. Else
// G = 0 says a branch is critical: ψ± = L ∓ R_a·Qp/(|n|²ρ), so the near line
// has sign L = sign Qp, the far one the opposite, both when L = Qp = 0. A near
// line shorter than `contact` is a contact point, as in fast/ (the given
// doubles often miss a contact by an ulp or so).
int lines_at(const PairFrame& f, const PointB& p, bool on_axis, bool touching, int xshift, double contact) {
  if (on_axis) {
    const int s = sign_on_b(f, f.axis_test, p);
    return s < 0 ? 2 : (s == 0 ? 1 : 0);
  }
  if (touching && sign_filtered(f, f.hnum, p, xshift) == 0 && sign_filtered(f, f.sphere, p, xshift) == 0)
    return sign_filtered(f, f.L, p, xshift) == 0 ? 1 : 0;
  const int sl = sign_filtered(f, f.L, p, xshift), sq = sign_filtered(f, f.Qp, p, xshift);
  if (sl == 0 && sq == 0) return 2;
  if (sl == sq) {
    const Iv X = x_enclosure(p.x, 128 + xshift);
    const Iv d = dist_enclosure(f, delta_of(f, X, y_of(f, X, p.sigma)));
    Fr hi(d.prec());
    mpfi_get_right(hi.get(), d.get());
    if (mpfr_cmp_d(hi.get(), contact) <= 0) return 0;
  }
  return 1;
}

// fast/'s contact length: 64ε times the power of two just above
// max(radii, max |C_b - C_a| component), for one definition of a line.
double contact_length(const PairFrame& f) {
  double s = std::max(std::abs(f.Ra.get_d()), std::abs(f.rb.get_d()));
  for (int i = 0; i < 3; ++i) s = std::max(s, std::abs(f.D[i].get_d()));
  if (!(s > 0)) return 0;
  int e;
  std::frexp(s, &e);
  return 64 * std::numeric_limits<double>::epsilon() * std::ldexp(1.0, e);
}

CandidateSet find_candidates(const PairFrame& f, bool touching) {
  static const AK ak;
  PROF(find_candidates);
  const int xshift = xshift_for(f);
  const double contact = contact_length(f);
  CandidateSet cs;
  const std::vector<PointB> crossings = axis_crossings(
      f, [&](const BiPoly& p, const PointB& pt) { return sign_filtered(f, p, pt, xshift); });
  auto add = [&](const PointB& p, bool continuum) {
    for (const Candidate& c : cs.list)
      if (same_point(c.pt, p)) return;
    Candidate c;
    c.pt = p;
    c.continuum = continuum;
    cs.list.push_back(c);
  };

  UPoly A, B;
  reduce_on_ellipse(f.G, f.s, &A, &B);
  const UPoly H = A * A - f.s * (B * B);
  if (!H.is_zero()) {
    std::vector<Real1> roots;
    {
      PROF(solve_H);
      ak.solve_1_object()(to_integer_poly(H), false, std::back_inserter(roots));
    }
    PROF(filter_roots);
    // Interval versions of G and |n×Δ|², converted once per precision.
    const IvBiPoly G64(f.G, 64 + kGuardBits), G192(f.G, 192 + kGuardBits);
    const IvBiPoly R64(f.rho2num, 64 + kGuardBits);
    for (const Real1& x : roots) {
      const Iv X64 = x_enclosure(x, 64 + xshift);
      int ss = iv_sign(s_of(f, X64));
      if (ss == 0) ss = sign_s_filtered(f, x, xshift);
      if (ss < 0) continue;
      std::vector<int> sigmas;
      if (ss == 0) {
        sigmas.push_back(0);  // G(x, 0) = A(x) and H(x) = A(x)²: a root
      } else {
        // H = (A + √s B)(A − √s B): one factor is zero. A factor proven nonzero
        // by intervals proves the other zero; only ties go to the exact test.
        int zp = -1, zm = -1;
        for (int bits : {64, 192}) {
          const Iv X = bits == 64 ? X64 : x_enclosure(x, bits + xshift);
          const Iv Y = y_of(f, X, 1), Ym = neg(Y);
          const IvBiPoly& G = bits == 64 ? G64 : G192;
          const bool np = !mpfi_has_zero(G.eval(X, Y).get());
          const bool nm = !mpfi_has_zero(G.eval(X, Ym).get());
          if (np != nm) {
            zp = np ? 0 : 1;
            zm = nm ? 0 : 1;
            break;
          }
        }
        if (zp < 0) {
          PROF(exact_G);
          zp = sign_on_b(f, f.G, PointB{x, 1}) == 0;
          zm = sign_on_b(f, f.G, PointB{x, -1}) == 0;
        }
        if (zp) sigmas.push_back(1);
        if (zm) sigmas.push_back(-1);
      }
      for (int sigma : sigmas) {
        const PointB p{x, sigma};
        int sr = iv_sign(R64.eval(X64, y_of(f, X64, sigma)));
        const bool on_axis = (sr != 0 ? sr : sign_filtered(f, f.rho2num, p, xshift)) == 0;
        add(p, on_axis);
        cs.binormals += lines_at(f, p, on_axis, touching, xshift, contact);
      }
    }
    return cs;
  }

  // H ≡ 0 (Villarceau pairs, meridian circles): G vanishes on all of b, so on
  // every arc between axis crossings either f is constant or f' ∝ L.
  cs.h_zero = true;
  cs.binormals = -1;
  for (const PointB& p : crossings) add(p, true);
  const mpq_class l0 = f.L.c[0][0], lx = f.L.c[1][0], ly = f.L.c[0][1];
  if (sgn(lx) != 0 || sgn(ly) != 0)
    for (const PointB& p : points_on_line(f, l0, lx, ly)) add(p, false);
  if (crossings.empty()) {
    // One arc, the whole circle: constant iff the near branch is critical at a
    // point where L != 0 (there L and Q' agree in sign), or L ≡ 0.
    std::vector<PointB> samples;
    const Real1 zero = ak.construct_algebraic_real_1_object()(0);
    samples.push_back({zero, 1});
    samples.push_back({zero, -1});
    for (const PointB& p : points_on_line(f, 0, 0, 1)) samples.push_back(p);  // y = 0
    bool constant = f.L.is_zero();
    for (const PointB& p : samples) {
      const int sl = sign_on_b(f, f.L, p);
      if (sl == 0) continue;
      constant = sl == sign_on_b(f, f.Qp, p);
      break;
    }
    add(samples.front(), constant);
    if (constant)
      for (Candidate& c : cs.list) c.continuum = true;
  }
  return cs;
}

// Exact contact test: the points of b on the plane of a (at most 2), or the
// 2D test when the circles are coplanar.
std::optional<Vec3> contact_point(const PairFrame& f, const Circle3& a, const Circle3& b) {
  static const AK ak;
  PROF(contact);
  const mpq_class c0 = f.hnum.c[0][0], c1 = f.hnum.c[1][0], c2 = f.hnum.c[0][1];
  if (sgn(c1) == 0 && sgn(c2) == 0) {
    if (sgn(c0) != 0) return std::nullopt;  // parallel planes
    // Coplanar: |R_a − R_b| <= |C_a − C_b| <= R_a + R_b, in exact squares.
    mpq_class d2 = 0;
    for (int i = 0; i < 3; ++i) d2 += f.D[i] * f.D[i];
    const mpq_class dm = f.Ra - f.rb, dp = f.Ra + f.rb;
    if (d2 < dm * dm || d2 > dp * dp) return std::nullopt;
    // A shared point, for the witness only (double is enough there).
    const Vec3 D = b.center - a.center;
    const double dl = D.norm();
    if (dl == 0.0) return any_point_on_a(a);
    const double t = (dl * dl + a.radius * a.radius - b.radius * b.radius) / (2 * dl);
    const double hgt = std::sqrt(std::max(0.0, a.radius * a.radius - t * t));
    const Vec3 w = a.normal.cross(D).normalized();
    return Vec3(a.center + t * D / dl + hgt * w);
  }
  for (const PointB& p : points_on_line(f, c0, c1, c2)) {
    if (sign_on_b(f, f.sphere, p) != 0) continue;
    const auto ab = ak.approximate_absolute_1_object()(p.x, 80);
    const mpfr_prec_t pr = 128;
    const Iv X = iv_of_interval(pr, mpq_class(ab.first.mpq()), mpq_class(ab.second.mpq()));
    const auto d = delta_of(f, X, y_of(f, X, p.sigma));
    return Vec3(mid_vec(d) + a.center);
  }
  return std::nullopt;
}

ExactCircleResult general_case(const Circle3& a, const Circle3& b, const PairFrame& f,
                               double target, int max_bits) {
  ExactCircleResult r;
  const std::optional<Vec3> touch = contact_point(f, a, b);
  CandidateSet cs = find_candidates(f, touch.has_value());
  r.binormals = cs.binormals;
  if (touch) {
    set_contact(r, *touch);
    return r;
  }
  if (cs.list.empty()) return not_certified("no candidate point on circle b (internal error)");

  const int xshift = xshift_for(f);
  Fr L, U;
  int best = -1;
  bool reached = false;
  for (int bits = kStartBits;; bits *= 2) {
    // Refine only the candidates that can still be the minimum.
    for (Candidate& c : cs.list)
      if (!c.evaluated || (best >= 0 && mpfr_cmp(c.lo.get(), U.get()) <= 0)) evaluate(f, c, bits, xshift);
    best = -1;
    for (size_t i = 0; i < cs.list.size(); ++i) {
      const Candidate& c = cs.list[i];
      if (best < 0 || mpfr_cmp(c.hi.get(), cs.list[best].hi.get()) < 0) best = static_cast<int>(i);
    }
    U = cs.list[best].hi;
    L = cs.list[0].lo;
    for (const Candidate& c : cs.list)
      if (mpfr_cmp(c.lo.get(), L.get()) < 0) L = c.lo;
    Fr w(std::max(mpfr_get_prec(L.get()), mpfr_get_prec(U.get())));
    mpfr_sub(w.get(), U.get(), L.get(), MPFR_RNDU);
    if (narrow_enough(L.get(), U.get(), w.get(), target)) {
      reached = true;
      break;
    }
    if (2 * bits > max_bits) break;
  }
  if (!mpfr_number_p(U.get())) return not_certified("no genuine point of b found for the upper bound");
  set_interval(r, L.get(), U.get());
  if (!reached) {
    r.status = ExactStatus::not_certified;
    r.reason = "width target not reached at max_precision_bits (interval still proven)";
  }

  // Multiplicity of the minimum: decided when every candidate that may attain
  // it agrees; on a tie between kinds, the one with the best upper bound wins.
  bool any_cont = false, any_fin = false;
  for (const Candidate& c : cs.list)
    if (mpfr_cmp(c.lo.get(), U.get()) <= 0) (c.continuum ? any_cont : any_fin) = true;
  const bool continuum = any_cont && (!any_fin || cs.list[best].continuum);
  if (continuum && r.status == ExactStatus::ok) r.status = ExactStatus::infinitely_many;

  // Witnesses at the genuine point that gave the upper bound.
  const Candidate& c = cs.list[best];
  const mpfr_prec_t p = 160;
  const Iv Xt(p, c.xt);
  const auto d = delta_of(f, Xt, y_of(f, Xt, c.st));
  r.point_b = mid_vec(d) + a.center;
  r.point_a = near_point_on_a(f, a, d);
  return r;
}

ExactCircleResult compute(const Circle3& a, const Circle3& b, const ExactOptions& options) {
  if (!is_finite(a) || !is_finite(b)) return not_certified("non-finite input");
  if (a.radius < 0 || b.radius < 0) return not_certified("negative radius");
  if ((a.radius > 0 && a.normal.isZero(0)) || (b.radius > 0 && b.normal.isZero(0)))
    return not_certified("zero normal on a circle of positive radius");
  const double scale =
      std::max({a.radius, b.radius, (a.center - b.center).norm(), std::numeric_limits<double>::min()});
  const double target = options.relative_width * scale;
  const int max_bits = std::max(options.max_precision_bits, kStartBits);

  // Radius 0: a point. Point–point, then point–circle with the point as b.
  if (a.radius == 0 && b.radius == 0) return point_point(a, b, target, max_bits);
  if (b.radius == 0) return point_circle(a, b, target, max_bits);
  if (a.radius == 0) {
    ExactCircleResult r = point_circle(b, a, target, max_bits);
    swap_sides(r);  // the same lines seen from the other side
    return r;
  }

  std::optional<PairFrame> fo;
  {
    PROF(make_frame);
    fo.emplace(make_frame(a, b));
  }
  const PairFrame& f = *fo;
  // Coaxial (incl. concentric coplanar): √(ΔR² + h²), every pair equidistant.
  const mpq_class nxnb0 = f.n[1] * f.nb[2] - f.n[2] * f.nb[1], nxnb1 = f.n[2] * f.nb[0] - f.n[0] * f.nb[2],
                  nxnb2 = f.n[0] * f.nb[1] - f.n[1] * f.nb[0];
  const mpq_class nxD0 = f.n[1] * f.D[2] - f.n[2] * f.D[1], nxD1 = f.n[2] * f.D[0] - f.n[0] * f.D[2],
                  nxD2 = f.n[0] * f.D[1] - f.n[1] * f.D[0];
  if (sgn(nxnb0) == 0 && sgn(nxnb1) == 0 && sgn(nxnb2) == 0 && sgn(nxD0) == 0 && sgn(nxD1) == 0 &&
      sgn(nxD2) == 0) {
    ExactCircleResult r;
    r.status = ExactStatus::infinitely_many;
    r.binormals = -1;
    const mpq_class hn = f.n[0] * f.D[0] + f.n[1] * f.D[1] + f.n[2] * f.D[2];
    r.point_a = any_point_on_a(a);
    const Vec3 w = (r.point_a - a.center) / a.radius;
    r.point_b = b.center + b.radius * w;
    if (sgn(hn) == 0 && f.Ra == f.rb) {
      set_contact(r, r.point_a);
      return r;
    }
    enclose_closed_form(
        [&](mpfr_prec_t p) {
          const Iv h = Iv(p, hn) / sqrt_nonneg(Iv(p, f.n2));
          return hypot(h, Iv(p, f.Ra - f.rb));
        },
        target, max_bits, r);
    return r;
  }
  return general_case(a, b, f, target, max_bits);
}

}  // namespace

ExactCircleResult circle3_circle3_distance_exact(const Circle3& a, const Circle3& b,
                                                 const ExactOptions& options) {
  try {
    return compute(a, b, options);
  } catch (const std::exception& e) {
    return not_certified(std::string("exception: ") + e.what());
  } catch (...) {
    return not_certified("unknown exception");
  }
}

}  // namespace revdist
