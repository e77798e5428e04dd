// Near-contact motion frames for the benchmarks (paper section 5): smooth rigid
// motion, the gap solved per frame so it follows a planned curve near contact.
#include "compare/motion.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace revdist {

namespace {

Vec3 random_unit(std::mt19937_64& g) {
  std::normal_distribution<double> N(0, 1);
  Vec3 v;
  do { v = Vec3(N(g), N(g), N(g)); } while (v.squaredNorm() < 1e-12);
  return v.normalized();
}

Mat3 random_rotation(std::mt19937_64& g) {
  std::normal_distribution<double> N(0, 1);
  return Eigen::Quaterniond(Eigen::Vector4d(N(g), N(g), N(g), N(g)).normalized()).toRotationMatrix();
}

Mat3 turn(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis).toRotationMatrix(); }

double mid_height(const Profile& p) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Piece& piece : p.pieces)
    for (const Vec2& q : piece.points) lo = std::min(lo, q.y()), hi = std::max(hi, q.y());
  return std::isfinite(lo) ? 0.5 * (lo + hi) : 0.0;
}

// The gap along one frame's approach line: b's centre at a's centre + s u.
struct Approach {
  PosedSolid A, B;
  Vec3 centre_a, offset_b, u;
  DistanceOptions options;
  int evaluations = 0;
  // The distance at separation s; -1 when the solids overlap or may (the
  // budget ran out with the lower bound at 0: slightly overlapping poses can
  // take the engine very long to prove, and the setup needs no proof).
  double gap(double s) {
    B.t = centre_a + s * u - offset_b;
    ++evaluations;
    const SolidDistanceResult r = solid_distance(A, B, options);
    if (r.overlap || (!r.converged && r.lower <= 0)) return -1.0;
    return r.converged ? r.distance : r.upper;
  }
};

}  // namespace

double profile_extent(const Profile& p) {
  double r = 0, lo = INFINITY, hi = -INFINITY;
  for (const Piece& piece : p.pieces)
    for (const Vec2& q : piece.points) r = std::max(r, q.x()), lo = std::min(lo, q.y()), hi = std::max(hi, q.y());
  return std::isfinite(lo) ? std::max(2 * r, hi - lo) : 0.0;
}

double profile_reach(const Profile& p) {
  double reach = 0;
  for (const Piece& piece : p.pieces)
    for (const Vec2& q : piece.points) reach = std::max(reach, q.norm());  // control points bound the curve
  return reach;
}

std::vector<MotionFrame> near_contact_motion(const PosedSolid& a, const ShapeAt& b, const MotionOptions& o) {
  std::mt19937_64 g(o.seed);
  const PosedSolid b0 = b(0);
  const double size = std::max(profile_extent(*a.profile), profile_extent(*b0.profile));
  const double delta = o.clearance * size;
  const double far = 2 * (profile_reach(*a.profile) + profile_reach(*b0.profile)) + delta;
  const Vec3 axis_a = random_unit(g), axis_b = random_unit(g);
  const Mat3 Rb0 = random_rotation(g);
  const Vec3 e1 = random_unit(g);
  const Vec3 e2 = e1.cross(random_unit(g)).normalized();
  const Vec3 e3 = e1.cross(e2);
  const double phase = std::uniform_real_distribution<double>(0, 2 * M_PI)(g);
  const double accept = 0.05 * delta;  // the gap is held this close to its plan

  Approach ap;
  ap.options.tol = 0.2 * accept;  // setup only: well inside the acceptance band
  ap.options.max_node_pairs = 20000;
  std::vector<MotionFrame> frames;
  double s_prev = far, s_prev2 = far, slope = 1.0;
  for (int j = 0; j < o.frames; ++j) {
    const double tau = o.frames > 1 ? static_cast<double>(j) / o.frames : 0.0;
    MotionFrame f;
    f.R_WA = turn(axis_a, 2 * M_PI * tau) * a.R;
    f.R_WB = turn(axis_b, 4 * M_PI * tau) * Rb0;
    f.t_WA = a.t;
    f.target = delta * (1 + o.swing * std::sin(2 * M_PI * o.gap_cycles * tau + phase));
    ap.A = a;
    ap.A.R = f.R_WA;
    ap.B = b(j);
    ap.B.R = f.R_WB;
    ap.centre_a = f.R_WA * Vec3(0, 0, mid_height(*a.profile)) + f.t_WA;
    ap.offset_b = f.R_WB * Vec3(0, 0, mid_height(*ap.B.profile));
    ap.u = (std::cos(2 * M_PI * tau) * e1 + std::sin(2 * M_PI * tau) * e2 + 0.4 * std::sin(4 * M_PI * tau) * e3)
               .normalized();
    // Touching and overlapping frames: solve for a small positive gap, then push in.
    const double goal = std::max(f.target, 3 * accept);

    // Start where the last two frames point (smooth motion: often already within the
    // band, one query per frame); below the goal, step out until the gap exceeds it.
    double s = std::min(far, 2 * s_prev - s_prev2), d = ap.gap(s);
    double s_lo = 0, d_lo = 0;
    bool have_lo = false;
    if (d <= goal && std::abs(d - goal) > accept) {
      s_lo = s, d_lo = std::max(d, 0.0), have_lo = true;
      for (double step = std::max(1.5 * (goal - d_lo), accept); d <= goal && s < far; step *= 2) {
        s = std::min(far, s + step), d = ap.gap(s);
        if (d <= goal) s_lo = s, d_lo = std::max(d, 0.0);
      }
    }
    double s_hi = s, d_hi = d;
    for (int it = 0; it < 60 && std::abs(d - goal) > accept; ++it) {
      if (have_lo) {
        // Regula falsi kept inside the middle 80 % of the bracket, so it always shrinks.
        const double w = s_hi - s_lo;
        s = s_hi - (d_hi - goal) * w / std::max(d_hi - d_lo, 1e-300);
        s = std::clamp(s, s_lo + 0.1 * w, s_hi - 0.1 * w);
      } else {
        // Lipschitz (slope 1) steps never cross the root; a smaller measured slope goes
        // faster. Never more than halfway to the centres, where the solids overlap.
        s = std::max(s_hi - (d_hi - goal) / slope, 0.5 * s_hi);
      }
      d = ap.gap(s);
      if (d > goal) {
        // A gap that grew while approaching (a concave part, or past a side) says nothing
        // of the slope at the root: back to the safe slope 1.
        slope = d < d_hi && s_hi - s > 1e-12 * size ? std::clamp((d_hi - d) / (s_hi - s), 0.05, 1.0) : 1.0;
        s_hi = s, d_hi = d;
      } else {
        s_lo = s, d_lo = std::max(d, 0.0), have_lo = true;
      }
    }
    s_prev2 = j == 0 ? s : s_prev, s_prev = s;
    f.achieved = f.target < goal ? 0.0 : d;
    f.evaluations = ap.evaluations;
    ap.evaluations = 0;
    // Push in along the approach by the planned shortfall (overlap depth for negative targets).
    f.t_WB = ap.centre_a + (s - (goal - f.target)) * ap.u - ap.offset_b;
    frames.push_back(f);
  }
  return frames;
}

}  // namespace revdist
