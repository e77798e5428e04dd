// Test helpers for the solid distance (fast/solid_distance): a brute force on
// the true (input) surfaces, a point-in-solid test on the true profile, random
// rigid motions, and the case transforms of the metamorphic checks (scale by a
// power of two, reversed profile direction). Independent of the engine: only
// core/ evaluation is used, never the biarc trees.
//
// The brute force rests on one fact (fast/biarc_tree.h): a point's distance to
// a surface of revolution is its distance, in its own meridian half-plane, to
// the profile. Every value it returns is |x - y| for genuine points x, y of the
// two surfaces, so it is never below the true surface distance, and (surfaces
// apart, neither solid inside the other) never below the solid distance either;
// the engine's `lower` must never exceed it.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/curve_eval.h"
#include "core/polyline_parity.h"
#include "core/pose.h"
#include "core/profile.h"
#include "fast/solid_distance.h"

namespace revdist::solid_test {

// The seed of a random test: REVDIST_SEED overrides the fallback; printed so a
// failure can be replayed.
inline std::uint64_t test_seed(std::uint64_t fallback, const char* what) {
  const char* s = std::getenv("REVDIST_SEED");
  const std::uint64_t seed = s ? std::strtoull(s, nullptr, 10) : fallback;
  std::printf("[ seed     ] %s: REVDIST_SEED=%llu\n", what, static_cast<unsigned long long>(seed));
  return seed;
}

inline std::string source_path(const std::string& rel) { return std::string(REVDIST_SOURCE_DIR) + "/" + rel; }

// Largest |coordinate| of a profile's control points: the size that scales tolerances.
inline double profile_scale(const Profile& p) {
  double s = 0.0;
  for (const Piece& piece : p.pieces)
    for (const Vec2& q : piece.points) s = std::max({s, std::abs(q.x()), std::abs(q.y())});
  return s;
}

// World coordinate scale of a query: translations and profile sizes.
inline double query_scale(const PosedSolid& a, const PosedSolid& b) {
  return std::max({profile_scale(*a.profile), profile_scale(*b.profile), a.t.cwiseAbs().maxCoeff(),
                   b.t.cwiseAbs().maxCoeff(), 1e-300});
}

inline Vec2 local_rz(const PosedSolid& s, const Vec3& x_W, Vec3* e_r = nullptr) {
  const Vec3 d = s.R.transpose() * (x_W - s.t);
  const double rho = std::hypot(d.x(), d.y());
  if (e_r) *e_r = rho > 0 ? Vec3(d.x() / rho, d.y() / rho, 0.0) : Vec3::UnitX();
  return Vec2(rho, d.z());
}

inline Vec3 world_of(const PosedSolid& s, const Vec2& q, double theta) {
  return s.R * Vec3(q.x() * std::cos(theta), q.x() * std::sin(theta), q.y()) + s.t;
}

// Dense samples of a profile's input curves, for 2D distances and ray crossings.
class ProfileSampler {
 public:
  ProfileSampler(const Profile& p, int per_piece) : prof_(&p) {
    for (std::size_t k = 0; k < p.pieces.size(); ++k) {
      const auto [u0, u1] = piece_domain(p.pieces[k]);
      for (int i = 0; i <= per_piece; ++i) {
        const double u = i == per_piece ? u1 : u0 + (u1 - u0) * i / per_piece;
        pts_.push_back(piece_point(p.pieces[k], u));
        piece_.push_back(static_cast<int>(k));
        u_.push_back(u);
        step_.push_back((u1 - u0) / per_piece);
      }
      double h = 0.0;
      for (std::size_t i = pts_.size() - per_piece; i < pts_.size(); ++i) {
        h = std::max(h, (pts_[i] - pts_[i - 1]).norm());
        // How far the curve strays from this chord, measured at the middle
        // parameter: the polyline's band around the curve.
        const Vec2 a = pts_[i - 1], e = pts_[i] - a;
        const Vec2 m = piece_point(p.pieces[k], 0.5 * (u_[i - 1] + u_[i])) - a;
        const double e2 = e.squaredNorm();
        const double t = e2 > 0 ? std::clamp(m.dot(e) / e2, 0.0, 1.0) : 0.0;
        band_ = std::max(band_, (m - t * e).norm());
      }
      half_chord_.push_back(0.5 * h + 1e-300);
    }
  }

  // The polyline's largest measured distance from the curve (its sagitta),
  // times 4 for what the middle samples miss: inside_polyline may misjudge a
  // point within this band of the curve (it lies between chord and curve).
  double band() const { return 4 * band_; }

  // Distance from q to the profile curves: per piece, the nearest sample
  // refined by a golden-section search on the piece's parameter (every piece
  // whose nearest sample is within its half chord of the best: a corner sample
  // belongs to two pieces, and the nearer curve may be the other one). Every
  // point evaluated lies on the curve, so the result is never below the true
  // distance (to rounding).
  double distance(const Vec2& q, Vec2* foot = nullptr) const {
    const std::size_t np = prof_->pieces.size();
    best_i_.assign(np, 0);
    best_d2_.assign(np, INFINITY);
    double b2 = INFINITY;
    for (std::size_t i = 0; i < pts_.size(); ++i) {
      const double d2 = (pts_[i] - q).squaredNorm();
      if (d2 < best_d2_[piece_[i]]) best_d2_[piece_[i]] = d2, best_i_[piece_[i]] = i;
    }
    Vec2 f = pts_[best_i_[0]];
    for (std::size_t k = 0; k < np; ++k)
      if (best_d2_[k] < b2) b2 = best_d2_[k], f = pts_[best_i_[k]];
    const double bd = std::sqrt(b2);
    for (std::size_t k = 0; k < np; ++k) {
      if (std::sqrt(best_d2_[k]) - half_chord_[k] > bd) continue;
      const std::size_t i = best_i_[k];
      const Piece& piece = prof_->pieces[k];
      const auto [lo, hi] = piece_domain(piece);
      double a = std::max(lo, u_[i] - step_[i]), b = std::min(hi, u_[i] + step_[i]);
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      auto eval = [&](double u) {
        const Vec2 p = piece_point(piece, u);
        const double d2 = (p - q).squaredNorm();
        if (d2 < b2) b2 = d2, f = p;
        return d2;
      };
      double c = b - g * (b - a), e = a + g * (b - a), fc = eval(c), fe = eval(e);
      for (int it = 0; it < 50 && b - a > 0; ++it) {
        if (fc < fe) { b = e; e = c; fe = fc; c = b - g * (b - a); fc = eval(c); }
        else { a = c; c = e; fc = fe; e = a + g * (b - a); fe = eval(e); }
      }
    }
    if (foot) *foot = f;
    return std::sqrt(b2);
  }

  // Ray crossings of {(r, q.z) : r > q.r} with the sample polyline (half-open
  // in z). Right for the true curve when q is farther from it than the
  // polyline's chordal error.
  bool inside_polyline(const Vec2& q) const { return polyline_inside(pts_, piece_, q); }

  const Profile& profile() const { return *prof_; }

 private:
  const Profile* prof_;
  std::vector<Vec2> pts_;
  std::vector<int> piece_;
  std::vector<double> u_, step_, half_chord_;
  double band_ = 0.0;
  mutable std::vector<std::size_t> best_i_;  // scratch (one sampler per thread)
  mutable std::vector<double> best_d2_;
};

enum class TrueSide { inside, outside, boundary };

// Side of local point q for the solid bounded by the true profile: boundary
// within `on` of the curve, else by ray crossing (the polyline is dense enough
// that its chordal error is far below `on` for the bundled models).
// Within `on` of the curve, or within the polyline's band where its inside
// test cannot tell (stress trial 191, lightmil in cup: the engine's shared
// point, proven inside both by the certified engine too, lay between a chord
// and the curve and was called outside), the point is on the boundary.
inline TrueSide true_side(const ProfileSampler& s, const Vec2& q, double on) {
  if (s.distance(q) <= std::max(on, s.band())) return TrueSide::boundary;
  return s.inside_polyline(q) ? TrueSide::inside : TrueSide::outside;
}

// Dense brute force of the distance between the two posed surfaces. Coarse:
// a grid of points of A (n_u per piece, n_theta around the axis), each against
// B's profile in B's meridian plane; then the best grid points are polished by
// a pattern search over (u, theta) of A. Then the same with A and B swapped.
// Returns a genuine |x - y| (x_W on A, y_W on B), an upper bound of the surface
// distance and, to the grid's resolution, close to it.
struct BruteResult {
  double distance = INFINITY;
  Vec3 x_W = Vec3::Zero(), y_W = Vec3::Zero();
};

namespace detail {

inline void brute_one_way(const PosedSolid& A, const PosedSolid& B, const ProfileSampler& sb, int n_u, int n_theta,
                          BruteResult* out, bool swapped) {
  const Profile& pa = *A.profile;
  struct Cand {
    double d;
    int piece;
    double u, th;
  };
  std::vector<Cand> cands;
  auto eval = [&](int k, double u, double th, Vec3* x, Vec3* y) {
    const Vec2 q = piece_point(pa.pieces[k], u);
    const Vec3 xw = world_of(A, q, th);
    Vec3 e_r;
    const Vec2 l = local_rz(B, xw, &e_r);
    Vec2 foot;
    const double d = sb.distance(l, &foot);
    if (x) *x = xw;
    if (y) *y = B.R * Vec3(foot.x() * e_r.x(), foot.x() * e_r.y(), foot.y()) + B.t;
    return d;
  };
  for (std::size_t k = 0; k < pa.pieces.size(); ++k) {
    const auto [u0, u1] = piece_domain(pa.pieces[k]);
    for (int i = 0; i <= n_u; ++i) {
      const double u = u0 + (u1 - u0) * i / n_u;
      for (int j = 0; j < n_theta; ++j) {
        const double th = 2 * M_PI * j / n_theta;
        cands.push_back({eval(static_cast<int>(k), u, th, nullptr, nullptr), static_cast<int>(k), u, th});
      }
    }
  }
  const std::size_t keep = std::min<std::size_t>(8, cands.size());
  std::partial_sort(cands.begin(), cands.begin() + keep, cands.end(),
                    [](const Cand& a, const Cand& b) { return a.d < b.d; });
  for (std::size_t c = 0; c < keep; ++c) {
    Cand cur = cands[c];
    const auto [u0, u1] = piece_domain(pa.pieces[cur.piece]);
    double du = (u1 - u0) / n_u, dth = 2 * M_PI / n_theta;
    while (du > 1e-13 * (u1 - u0) || dth > 1e-13) {
      bool moved = false;
      const double tries[4][2] = {{du, 0}, {-du, 0}, {0, dth}, {0, -dth}};
      for (const auto& t : tries) {
        const double u = std::clamp(cur.u + t[0], u0, u1), th = cur.th + t[1];
        const double d = eval(cur.piece, u, th, nullptr, nullptr);
        if (d < cur.d) {
          cur = {d, cur.piece, u, th};
          moved = true;
        }
      }
      if (!moved) du *= 0.5, dth *= 0.5;
    }
    Vec3 x, y;
    const double d = eval(cur.piece, cur.u, cur.th, &x, &y);
    // The recomputed genuine pair (the foot is the last evaluated point).
    const double dd = (x - y).norm();
    (void)d;
    if (dd < out->distance) {
      out->distance = dd;
      out->x_W = swapped ? y : x;
      out->y_W = swapped ? x : y;
    }
  }
}

}  // namespace detail

inline BruteResult brute_surface_distance(const PosedSolid& A, const PosedSolid& B, int n_u = 48, int n_theta = 72,
                                          int per_piece = 96) {
  BruteResult r;
  const ProfileSampler sa(*A.profile, per_piece), sb(*B.profile, per_piece);
  detail::brute_one_way(A, B, sb, n_u, n_theta, &r, false);
  detail::brute_one_way(B, A, sa, n_u, n_theta, &r, true);
  return r;
}

// Uniformly random unit quaternion [w, x, y, z].
inline std::array<double, 4> random_quaternion(std::mt19937_64& g) {
  std::normal_distribution<double> N(0, 1);
  std::array<double, 4> q;
  double n = 0;
  do {
    for (double& c : q) c = N(g);
    n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  } while (n < 1e-3);
  for (double& c : q) c /= n;
  return q;
}

// A rotation within `angle` radians of the identity.
inline std::array<double, 4> near_identity_quaternion(std::mt19937_64& g, double angle) {
  std::normal_distribution<double> N(0, 1);
  Vec3 ax(N(g), N(g), N(g));
  ax.normalize();
  const double h = 0.5 * angle * std::uniform_real_distribution<double>(-1, 1)(g);
  return {std::cos(h), std::sin(h) * ax.x(), std::sin(h) * ax.y(), std::sin(h) * ax.z()};
}

inline Mat3 rotation_of(const std::array<double, 4>& q) {
  Pose p;
  p.q = q;
  return p.rotation();
}

// The same rigid motion x -> M x + m applied to a posed solid.
inline PosedSolid moved(const PosedSolid& s, const Mat3& M, const Vec3& m) {
  PosedSolid r = s;
  r.R = M * s.R;
  r.t = M * s.t + m;
  return r;
}

// Every control point times `f` (a power of two: exact), knots and weights unchanged.
inline Profile scaled_profile(const Profile& p, double f) {
  Profile r = p;
  for (Piece& piece : r.pieces)
    for (Vec2& q : piece.points) q *= f;
  return r;
}

// The same curve traversed the other way: pieces in reverse order, each
// piece's points and weights reversed, B-spline knots mirrored (u -> a + b - u).
inline Profile reversed_profile(const Profile& p) {
  Profile r = p;
  std::reverse(r.pieces.begin(), r.pieces.end());
  for (Piece& piece : r.pieces) {
    std::reverse(piece.points.begin(), piece.points.end());
    std::reverse(piece.weights.begin(), piece.weights.end());
    if (!piece.knots.empty()) {
      const double a = piece.knots.front(), b = piece.knots.back();
      std::vector<double> k(piece.knots.rbegin(), piece.knots.rend());
      for (double& x : k) x = (a + b) - x;
      k.front() = a;
      k.back() = b;
      piece.knots = k;
    }
  }
  return r;
}

inline std::string describe(const SolidDistanceResult& r) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "lower=%.17g upper=%.17g distance=%.17g overlap=%d converged=%d reason='%s' node_pairs=%ld "
                "leaf_pairs=%ld patch_pairs=%ld refined=%ld",
                r.lower, r.upper, r.distance, r.overlap, r.converged, r.reason.c_str(), r.stats.node_pairs,
                r.stats.leaf_pairs, r.stats.patch_pairs, r.stats.refined);
  return buf;
}

inline std::string describe_pose(const PosedSolid& s) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "R=[%.17g %.17g %.17g; %.17g %.17g %.17g; %.17g %.17g %.17g] t=[%.17g %.17g %.17g]",
                s.R(0, 0), s.R(0, 1), s.R(0, 2), s.R(1, 0), s.R(1, 1), s.R(1, 2), s.R(2, 0), s.R(2, 1), s.R(2, 2),
                s.t.x(), s.t.y(), s.t.z());
  return buf;
}

// Certificates of one result (SPEC section 6): witness points on their true
// surfaces, their distance within the bracket, overlap means a shared point.
// `on` is the accepted distance from the true profile (rounding of the world
// transform and of the engine's projection onto the curve).
inline void expect_certificates(const PosedSolid& A, const PosedSolid& B, const SolidDistanceResult& r,
                                const ProfileSampler& sa, const ProfileSampler& sb, double on,
                                const std::string& what) {
  const double scale = query_scale(A, B);
  const double round = 1e-12 * scale;  // rounding of the world transform and the bracket arithmetic
  EXPECT_LE(r.lower, r.upper) << what << " " << describe(r);
  EXPECT_GE(r.lower, 0.0) << what;
  // SPEC 6: an answer always carries a finite bracket (issue 10, item 15).
  if (!std::isfinite(r.upper)) {
    ADD_FAILURE() << what << " no finite upper bound: " << describe(r);
    return;
  }
  EXPECT_TRUE(r.lower <= r.distance && r.distance <= r.upper) << what << " " << describe(r);
  const Vec2 la = local_rz(A, r.point_a), lb = local_rz(B, r.point_b);
  if (r.overlap) {
    EXPECT_EQ(r.lower, 0.0) << what;
    EXPECT_EQ(r.upper, 0.0) << what;
    EXPECT_EQ(r.distance, 0.0) << what;
    EXPECT_EQ(r.point_a, r.point_b) << what;
    // The shared point: inside or on the boundary of both true solids.
    EXPECT_NE(true_side(sa, la, on), TrueSide::outside) << what << " point_a (r,z)=" << la.transpose();
    EXPECT_NE(true_side(sb, lb, on), TrueSide::outside) << what << " point_b (r,z)=" << lb.transpose();
    return;
  }
  EXPECT_LE(sa.distance(la), on) << what << " point_a not on A's true surface, (r,z)=" << la.transpose();
  EXPECT_LE(sb.distance(lb), on) << what << " point_b not on B's true surface, (r,z)=" << lb.transpose();
  const double w = (r.point_a - r.point_b).norm();
  EXPECT_LE(std::abs(w - r.distance), r.upper - r.lower + round) << what << " |pa-pb|=" << w << " " << describe(r);
  EXPECT_LE(w, r.upper + round) << what << " witnesses farther apart than upper";
  EXPECT_GE(w, r.lower - round) << what << " genuine witnesses closer than lower";
}

}  // namespace revdist::solid_test
