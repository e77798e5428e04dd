// Brute force on the true surfaces and the support function of a profile: the
// references of `revdist stress`, independent of fast/.
#include "compare/brute_force.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/curve_eval.h"
#include "core/polyline_parity.h"

namespace revdist {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Safeguarded Newton on phi(u) = (C(u) - q) . C'(u) inside [a, b]: the nearest
// point of one piece to q near a sample. Every evaluated point is on the curve;
// the best is kept.
double refine_foot(const Piece& piece, const Vec2& q, double a, double b, double u, Vec2* foot) {
  Vec2 d[3];
  double best = kInf;
  auto eval = [&](double x) {
    piece_derivatives(piece, x, 2, d);
    const double f = (d[0] - q).squaredNorm();
    if (f < best) best = f, *foot = d[0];
    return (d[0] - q).dot(d[1]);
  };
  double fa = eval(a), fb = eval(b);
  if (!(fa < 0 && fb > 0)) {  // no interior minimum bracketed: an end (both evaluated) or the sample
    eval(u);
    return std::sqrt(best);
  }
  for (int it = 0; it < 40 && b - a > 1e-15 * std::max(1.0, std::abs(a)); ++it) {
    const double phi = eval(u);
    if (phi < 0) a = u; else b = u;
    const double dphi = d[1].squaredNorm() + (d[0] - q).dot(d[2]);
    double next = dphi > 0 ? u - phi / dphi : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (std::abs(next - u) <= 1e-16 * std::max(1.0, std::abs(u))) break;
    u = next;
  }
  return std::sqrt(best);
}

}  // namespace

ProfileNearest::ProfileNearest(const Profile& profile, int samples_per_piece) : profile_(&profile) {
  for (std::size_t k = 0; k < profile.pieces.size(); ++k) {
    const auto [u0, u1] = piece_domain(profile.pieces[k]);
    for (int i = 0; i <= samples_per_piece; ++i) {
      const double u = i == samples_per_piece ? u1 : u0 + (u1 - u0) * i / samples_per_piece;
      pts_.push_back(piece_point(profile.pieces[k], u));
      piece_.push_back(static_cast<int>(k));
      u_.push_back(u);
      size_ = std::max({size_, std::abs(pts_.back().x()), std::abs(pts_.back().y())});
    }
  }
}

double ProfileNearest::distance(const Vec2& q, Vec2* foot) const {
  const std::size_t np = profile_->pieces.size();
  std::vector<std::size_t> best_i(np, 0);
  std::vector<double> best_d2(np, kInf);
  for (std::size_t i = 0; i < pts_.size(); ++i) {
    const double d2 = (pts_[i] - q).squaredNorm();
    if (d2 < best_d2[piece_[i]]) best_d2[piece_[i]] = d2, best_i[piece_[i]] = i;
  }
  double best = kInf;
  Vec2 f = Vec2::Zero();
  const double coarse = std::sqrt(*std::min_element(best_d2.begin(), best_d2.end()));
  for (std::size_t k = 0; k < np; ++k) {
    const std::size_t i = best_i[k];
    // A piece whose nearest sample is far beyond the best cannot hold the foot
    // (its curve is within a sample spacing of its samples).
    const double spacing = std::max(i > 0 && piece_[i - 1] == piece_[i] ? (pts_[i] - pts_[i - 1]).norm() : 0.0,
                                    i + 1 < pts_.size() && piece_[i + 1] == piece_[i] ? (pts_[i + 1] - pts_[i]).norm() : 0.0);
    if (std::sqrt(best_d2[k]) > coarse + spacing) continue;
    const double a = i > 0 && piece_[i - 1] == piece_[i] ? u_[i - 1] : u_[i];
    const double b = i + 1 < pts_.size() && piece_[i + 1] == piece_[i] ? u_[i + 1] : u_[i];
    Vec2 fk;
    const double d = refine_foot(profile_->pieces[k], q, a, b, u_[i], &fk);
    if (d < best) best = d, f = fk;
  }
  if (foot) *foot = f;
  return best;
}

bool ProfileNearest::inside(const Vec2& q) const { return polyline_inside(pts_, piece_, q); }

Vec2 PosedProfile::local_rz(const Vec3& x_W, Vec3* e_r) const {
  const Vec3 d = R.transpose() * (x_W - t);
  const double rho = std::hypot(d.x(), d.y());
  if (e_r) *e_r = rho > 0 ? Vec3(d.x() / rho, d.y() / rho, 0.0) : Vec3::UnitX();
  return Vec2(rho, d.z());
}

double PosedProfile::surface_distance(const Vec3& x_W) const { return nearest->distance(local_rz(x_W)); }

namespace {

struct Side {
  const PosedProfile* self;
  const PosedProfile* other;
  // The point of `self` at (piece k, u, theta), its distance to `other`, the
  // foot on `other` (world) and the gradient of the distance in (u, theta).
  double eval(int k, double u, double th, Vec3* x, Vec3* y, Vec2* grad) const {
    const Piece& piece = self->nearest->profile().pieces[k];
    Vec2 d[2];
    piece_derivatives(piece, u, 1, d);
    const double c = std::cos(th), s = std::sin(th);
    const Vec3 xw = self->R * Vec3(d[0].x() * c, d[0].x() * s, d[0].y()) + self->t;
    Vec3 e_r;
    const Vec2 l = other->local_rz(xw, &e_r);
    Vec2 foot;
    const double dist = other->nearest->distance(l, &foot);
    const Vec3 yw = other->R * Vec3(foot.x() * e_r.x(), foot.x() * e_r.y(), foot.y()) + other->t;
    if (x) *x = xw;
    if (y) *y = yw;
    if (grad) {
      // Envelope theorem: d dist / d p = (x - y) / |x - y| . dx / dp.
      const Vec3 n = dist > 0 ? Vec3((xw - yw) / std::max((xw - yw).norm(), 1e-300)) : Vec3::Zero();
      const Vec3 xu = self->R * Vec3(d[1].x() * c, d[1].x() * s, d[1].y());
      const Vec3 xt = self->R * Vec3(-d[0].x() * s, d[0].x() * c, 0.0);
      *grad = Vec2(n.dot(xu), n.dot(xt));
    }
    return dist;
  }
};

void one_way(const Side& side, int n_u, int n_theta, int keep, BruteResult* out) {
  struct Start {
    double d;
    int k;
    double u, th;
  };
  std::vector<Start> starts;
  const Profile& p = side.self->nearest->profile();
  for (std::size_t k = 0; k < p.pieces.size(); ++k) {
    const auto [u0, u1] = piece_domain(p.pieces[k]);
    for (int i = 0; i <= n_u; ++i) {
      const double u = i == n_u ? u1 : u0 + (u1 - u0) * i / n_u;
      for (int j = 0; j < n_theta; ++j) {
        const double th = 2 * M_PI * j / n_theta;
        starts.push_back({side.eval(static_cast<int>(k), u, th, nullptr, nullptr, nullptr), static_cast<int>(k), u, th});
      }
    }
  }
  const std::size_t m = std::min<std::size_t>(keep, starts.size());
  std::partial_sort(starts.begin(), starts.begin() + m, starts.end(),
                    [](const Start& a, const Start& b) { return a.d < b.d; });
  for (std::size_t c = 0; c < m; ++c) {
    Start cur = starts[c];
    const auto [u0, u1] = piece_domain(p.pieces[cur.k]);
    // Levenberg-Marquardt on (u, theta), Hessian from differences of the
    // analytic gradient; a step is kept only when the distance decreases.
    double lambda = 1e-3;
    Vec2 g;
    cur.d = side.eval(cur.k, cur.u, cur.th, nullptr, nullptr, &g);
    const double hu = 1e-7 * (u1 - u0), ht = 1e-7;
    for (int it = 0; it < 40 && cur.d > 0; ++it) {
      Vec2 gu, gt;
      side.eval(cur.k, std::min(u1, cur.u + hu), cur.th, nullptr, nullptr, &gu);
      side.eval(cur.k, cur.u, cur.th + ht, nullptr, nullptr, &gt);
      const double du_eff = std::min(u1, cur.u + hu) - cur.u;
      Eigen::Matrix2d H;
      H.col(0) = du_eff > 0 ? Vec2((gu - g) / du_eff) : Vec2(0, 0);
      H.col(1) = (gt - g) / ht;
      H = 0.5 * (H + H.transpose()).eval();
      bool improved = false;
      for (int tries = 0; tries < 8 && !improved; ++tries) {
        Eigen::Matrix2d A = H;
        A(0, 0) += lambda * (std::abs(H(0, 0)) + 1e-12);
        A(1, 1) += lambda * (std::abs(H(1, 1)) + 1e-12);
        Vec2 step = -A.ldlt().solve(g);
        if (!step.allFinite()) step = -1e-3 * g;
        const double u = std::clamp(cur.u + step.x(), u0, u1), th = cur.th + step.y();
        Vec2 gn;
        const double d = side.eval(cur.k, u, th, nullptr, nullptr, &gn);
        if (d < cur.d) {
          improved = std::abs(u - cur.u) + std::abs(th - cur.th) > 0;
          cur = {d, cur.k, u, th};
          g = gn;
          lambda = std::max(1e-9, lambda / 4);
        } else {
          lambda *= 8;
        }
      }
      if (!improved) break;
    }
    Vec3 x, y;
    side.eval(cur.k, cur.u, cur.th, &x, &y, nullptr);
    const double d = (x - y).norm();  // the genuine pair, recomputed
    if (d < out->distance) {
      out->distance = d;
      out->point_a = x;
      out->point_b = y;
    }
  }
}

}  // namespace

BruteResult brute_surface_distance(const PosedProfile& a, const PosedProfile& b, int n_u, int n_theta, int keep) {
  BruteResult r;
  r.distance = kInf;
  one_way(Side{&a, &b}, n_u, n_theta, keep, &r);
  BruteResult s;
  s.distance = kInf;
  one_way(Side{&b, &a}, n_u, n_theta, keep, &s);
  if (s.distance < r.distance) {
    r.distance = s.distance;
    r.point_a = s.point_b;
    r.point_b = s.point_a;
  }
  return r;
}

double profile_support(const Profile& profile, const Vec3& n_local) {
  const Vec2 d(std::hypot(n_local.x(), n_local.y()), n_local.z());
  double best = -kInf;
  for (const Piece& piece : profile.pieces) {
    best = std::max({best, piece.start().dot(d), piece.end().dot(d)});
    if (piece.kind == PieceKind::line) continue;
    if (piece.kind == PieceKind::arc) {
      // The arc's farthest point in direction d, if the sweep reaches it.
      const ArcGeometry g = arc_geometry(piece);
      double rel = std::atan2(d.y(), d.x()) - g.start_angle;
      if (g.sweep < 0) rel = -rel;
      rel = std::fmod(rel, 2 * M_PI);
      if (rel < 0) rel += 2 * M_PI;
      if (rel <= std::abs(g.sweep)) best = std::max(best, g.center.dot(d) + g.radius * d.norm());
      continue;
    }
    // Curves: the best sample, then Newton on C'(u) . d = 0 in its neighbourhood.
    const auto [u0, u1] = piece_domain(piece);
    const int n = 512;
    int bi = 0;
    double bv = -kInf;
    for (int i = 0; i <= n; ++i) {
      const double v = piece_point(piece, u0 + (u1 - u0) * i / n).dot(d);
      if (v > bv) bv = v, bi = i;
    }
    best = std::max(best, bv);
    double a = u0 + (u1 - u0) * std::max(0, bi - 1) / n, b = u0 + (u1 - u0) * std::min(n, bi + 1) / n;
    double u = u0 + (u1 - u0) * bi / n;
    Vec2 D[3];
    for (int it = 0; it < 60; ++it) {
      piece_derivatives(piece, u, 2, D);
      best = std::max(best, D[0].dot(d));
      const double f = D[1].dot(d), df = D[2].dot(d);
      if (f > 0) a = u; else b = u;
      double next = df < 0 ? u - f / df : 0.5 * (a + b);
      if (!(next > a && next < b)) next = 0.5 * (a + b);
      if (std::abs(next - u) <= 1e-16 * std::max(1.0, std::abs(u)) || b - a <= 0) break;
      u = next;
    }
  }
  return best;
}

}  // namespace revdist
