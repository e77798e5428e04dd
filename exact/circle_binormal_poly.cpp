// The binormal condition of two circles as rational polynomials (paper App. A,
// §3.2), and exact signs at points of circle b. Derivation: for P on b,
// Δ = P − C_a, the squared distance to a is f = |Δ|² + R² − 2Rρ with
// ρ² = |n×Δ|²/|n|². Along b (tangent T = n_b × (P − C_b)) f'/2 = L − R Q'/(|n|²ρ)
// with L = Δ·T = (C_b − C_a)·T and Q' = |n|²L − (Δ·n)(n·T); the far branch has
// the opposite sign. Their product, times |n|⁶ρ², is G = |n|²|n×Δ|²L² − R²Q'²:
// quartic in P, zero at every binormal foot (near or far) and at axis crossings.
#include <cassert>

#include "exact/circle_exact_internal.h"

namespace revdist::exact_detail {

// ---------------------------------------------------------------- UPoly
int UPoly::degree() const {
  for (int i = static_cast<int>(c.size()) - 1; i >= 0; --i)
    if (sgn(c[i]) != 0) return i;
  return -1;
}

UPoly operator+(const UPoly& p, const UPoly& q) {
  UPoly r;
  r.c.resize(std::max(p.c.size(), q.c.size()));
  for (size_t i = 0; i < p.c.size(); ++i) r.c[i] += p.c[i];
  for (size_t i = 0; i < q.c.size(); ++i) r.c[i] += q.c[i];
  return r;
}

UPoly operator-(const UPoly& p, const UPoly& q) { return p + mpq_class(-1) * q; }

UPoly operator*(const UPoly& p, const UPoly& q) {
  UPoly r;
  if (p.c.empty() || q.c.empty()) return r;
  r.c.resize(p.c.size() + q.c.size() - 1);
  for (size_t i = 0; i < p.c.size(); ++i) {
    if (sgn(p.c[i]) == 0) continue;
    for (size_t j = 0; j < q.c.size(); ++j) r.c[i + j] += p.c[i] * q.c[j];
  }
  return r;
}

UPoly operator*(const mpq_class& k, const UPoly& p) {
  UPoly r = p;
  for (auto& x : r.c) x *= k;
  return r;
}

mpq_class eval(const UPoly& p, const mpq_class& x) {
  mpq_class v = 0;
  for (int i = static_cast<int>(p.c.size()) - 1; i >= 0; --i) v = v * x + p.c[i];
  return v;
}

// ---------------------------------------------------------------- BiPoly
BiPoly BiPoly::linear(const mpq_class& c0, const mpq_class& cx, const mpq_class& cy) {
  BiPoly p;
  p.c[0][0] = c0;
  p.c[1][0] = cx;
  p.c[0][1] = cy;
  return p;
}

bool BiPoly::is_zero() const {
  for (const auto& row : c)
    for (const auto& x : row)
      if (sgn(x) != 0) return false;
  return true;
}

BiPoly operator+(const BiPoly& p, const BiPoly& q) {
  BiPoly r;
  for (int i = 0; i <= kMaxDeg; ++i)
    for (int j = 0; i + j <= kMaxDeg; ++j) r.c[i][j] = p.c[i][j] + q.c[i][j];
  return r;
}

BiPoly operator*(const mpq_class& k, const BiPoly& p) {
  BiPoly r;
  for (int i = 0; i <= kMaxDeg; ++i)
    for (int j = 0; i + j <= kMaxDeg; ++j) r.c[i][j] = k * p.c[i][j];
  return r;
}

BiPoly operator-(const BiPoly& p, const BiPoly& q) { return p + mpq_class(-1) * q; }

BiPoly operator*(const BiPoly& p, const BiPoly& q) {
  BiPoly r;
  for (int i = 0; i <= kMaxDeg; ++i)
    for (int j = 0; i + j <= kMaxDeg; ++j) {
      if (sgn(p.c[i][j]) == 0) continue;
      for (int k = 0; k <= kMaxDeg; ++k)
        for (int l = 0; k + l <= kMaxDeg; ++l) {
          if (sgn(q.c[k][l]) == 0) continue;
          assert(i + j + k + l <= kMaxDeg);
          r.c[i + k][j + l] += p.c[i][j] * q.c[k][l];
        }
    }
  return r;
}

namespace {

Q3 to_q(const Vec3& v) { return {mpq_class(v.x()), mpq_class(v.y()), mpq_class(v.z())}; }
Q3 sub(const Q3& a, const Q3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Q3 cross(const Q3& a, const Q3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dot(const Q3& a, const Q3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

BiPoly dot(const BiVec& a, const BiVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
BiPoly dot(const Q3& a, const BiVec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
BiVec cross(const Q3& a, const BiVec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

UPoly upoly(std::initializer_list<mpq_class> c) { return UPoly{std::vector<mpq_class>(c)}; }

}  // namespace

PairFrame make_frame(const Circle3& a, const Circle3& b) {
  PairFrame f;
  f.n = to_q(a.normal);
  f.n2 = dot(f.n, f.n);
  f.Ra = mpq_class(a.radius);
  f.Ra2 = f.Ra * f.Ra;
  f.ca = to_q(a.center);
  f.nb = to_q(b.normal);
  f.D = sub(to_q(b.center), f.ca);
  // e_k × n_b with k the smallest |n_b| component: the largest |u|.
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(b.normal[i]) < std::abs(b.normal[k])) k = i;
  Q3 ek{0, 0, 0};
  ek[k] = 1;
  f.u = cross(ek, f.nb);
  f.v = cross(f.nb, f.u);
  f.rb = mpq_class(b.radius);
  f.rb2 = f.rb * f.rb;
  f.alpha = dot(f.u, f.u);
  f.beta = f.alpha * dot(f.nb, f.nb);
  // A point (radius 0, maybe a zero normal) has no ellipse; s stays zero.
  if (sgn(f.beta) != 0) f.s = upoly({f.rb2 / f.beta, mpq_class(0), -f.alpha / f.beta});

  for (int i = 0; i < 3; ++i) f.delta[i] = BiPoly::linear(f.D[i], f.u[i], f.v[i]);
  // T = n_b × (x u + y v) = x v − y |n_b|² u.
  const mpq_class nb2 = dot(f.nb, f.nb);
  BiVec T;
  for (int i = 0; i < 3; ++i) T[i] = BiPoly::linear(0, f.v[i], -nb2 * f.u[i]);

  const BiVec nxd = cross(f.n, f.delta);
  f.rho2num = dot(nxd, nxd);
  f.hnum = dot(f.n, f.delta);
  f.L = dot(f.D, T);
  const BiPoly nT = dot(f.n, T);
  f.Qp = f.n2 * f.L - f.hnum * nT;
  f.G = f.n2 * f.rho2num * f.L * f.L - f.Ra2 * f.Qp * f.Qp;
  f.sphere = dot(f.delta, f.delta) - BiPoly::constant(f.Ra2);
  const BiVec nxT = cross(f.n, T);
  f.axis_test = f.n2 * f.L * f.L - f.Ra2 * dot(nxT, nxT);
  return f;
}

void reduce_on_ellipse(const BiPoly& p, const UPoly& s, UPoly* A, UPoly* B) {
  A->c.clear();
  B->c.clear();
  UPoly spow = upoly({1});  // s^(j/2) or s^((j-1)/2)
  for (int j = 0; j <= kMaxDeg; ++j) {
    UPoly col;
    col.c.resize(kMaxDeg + 1);
    for (int i = 0; i + j <= kMaxDeg; ++i) col.c[i] = p.c[i][j];
    if (j % 2 == 0) {
      *A = *A + col * spow;
    } else {
      *B = *B + col * spow;
      spow = spow * s;
    }
  }
}

Poly1Z to_integer_poly(const UPoly& p) {
  const int deg = p.degree();
  if (deg < 0) return Poly1Z(CGAL::Gmpz(0));
  mpz_class den = 1, content = 0;
  for (int i = 0; i <= deg; ++i) mpz_lcm(den.get_mpz_t(), den.get_mpz_t(), p.c[i].get_den_mpz_t());
  std::vector<mpz_class> z(deg + 1);
  for (int i = 0; i <= deg; ++i) {
    z[i] = p.c[i].get_num() * (den / p.c[i].get_den());
    mpz_gcd(content.get_mpz_t(), content.get_mpz_t(), z[i].get_mpz_t());
  }
  std::vector<CGAL::Gmpz> coeffs;
  coeffs.reserve(deg + 1);
  for (int i = 0; i <= deg; ++i) {
    mpz_class q = z[i] / content;
    coeffs.emplace_back(q.get_mpz_t());
  }
  return Poly1Z(coeffs.begin(), coeffs.end());
}

int sign_of_s(const PairFrame& f, const Real1& x) {
  static const AK ak;
  return static_cast<int>(ak.sign_at_1_object()(to_integer_poly(f.s), x));
}

int sign_on_b(const PairFrame& f, const BiPoly& p, const PointB& pt) {
  static const AK ak;
  const auto sign_at = ak.sign_at_1_object();
  UPoly c, d;
  reduce_on_ellipse(p, f.s, &c, &d);
  // p = c + y d with y = sigma √s.
  const int sc = c.is_zero() ? 0 : static_cast<int>(sign_at(to_integer_poly(c), pt.x));
  if (pt.sigma == 0) return sc;
  const int sd = d.is_zero() ? 0 : pt.sigma * static_cast<int>(sign_at(to_integer_poly(d), pt.x));
  if (sd == 0) return sc;
  if (sc == 0 || sc == sd) return sd;
  const UPoly diff = c * c - f.s * (d * d);
  const int sdiff = diff.is_zero() ? 0 : static_cast<int>(sign_at(to_integer_poly(diff), pt.x));
  if (sdiff == 0) return 0;
  return sdiff > 0 ? sc : sd;
}

std::vector<PointB> points_on_line(const PairFrame& f, const mpq_class& c0, const mpq_class& c1,
                                   const mpq_class& c2) {
  static const AK ak;
  std::vector<PointB> out;
  if (sgn(c2) != 0) {
    const mpq_class m0 = -c0 / c2, m1 = -c1 / c2;  // y = m0 + m1 x
    const UPoly q = upoly({f.beta * m0 * m0 - f.rb2, 2 * f.beta * m0 * m1, f.alpha + f.beta * m1 * m1});
    std::vector<Real1> roots;
    ak.solve_1_object()(to_integer_poly(q), false, std::back_inserter(roots));
    const UPoly yline = upoly({m0, m1});
    for (const Real1& x : roots) {
      PointB p{x, 0};
      if (!yline.is_zero()) p.sigma = static_cast<int>(ak.sign_at_1_object()(to_integer_poly(yline), x));
      out.push_back(p);
    }
    return out;
  }
  assert(sgn(c1) != 0);
  const mpq_class x0 = -c0 / c1;
  const Real1 xr = ak.construct_algebraic_real_1_object()(Bound(x0.get_mpq_t()));
  const int ss = sgn(eval(f.s, x0));
  if (ss == 0) out.push_back({xr, 0});
  if (ss > 0) {
    out.push_back({xr, 1});
    out.push_back({xr, -1});
  }
  return out;
}

std::vector<PointB> axis_crossings(const PairFrame& f, const SignOnB& sign) {
  std::vector<PointB> out;
  if (sgn(f.Ra) == 0) return out;  // a point has no axis worth naming
  // n × Δ = 0: three lines in (x, y); take one that is not degenerate and filter.
  const Q3 nxD = cross(f.n, f.D), nxu = cross(f.n, f.u), nxv = cross(f.n, f.v);
  int best = -1;
  for (int i = 0; i < 3; ++i)
    if (sgn(nxu[i]) != 0 || sgn(nxv[i]) != 0) {
      best = i;
      break;
    }
  if (best < 0) return out;
  for (const PointB& p : points_on_line(f, nxD[best], nxu[best], nxv[best]))
    if (sign(f.rho2num, p) == 0) out.push_back(p);
  return out;
}

bool same_point(const PointB& p, const PointB& q) {
  static const AK ak;
  return p.sigma == q.sigma && ak.compare_1_object()(p.x, q.x) == CGAL::EQUAL;
}

}  // namespace revdist::exact_detail
