// The stress families (issue 7): near-degenerate solid pairs built so their
// distance is known in closed form, and the circle-pair families of
// compare/circle_families.h. Two constructions give the solid distances:
//  - mirror pairs: B is A reflected in a plane {x . n = c}; as a reflection of a
//    solid of revolution is again one (the local mirror y -> -y maps it to
//    itself), B = (M R_A F, M t_A + 2 c n) with M = I - 2 n n^T, F = diag(1,-1,1),
//    and d(A, B) = 2 (c - h_A(n)) for h_A the support function of A: any x in A
//    and mirror(x') in B are at least dist(x, plane) + dist(x', plane) apart;
//  - tube pairs: a ring (torus) and a sphere are the points within r of a circle
//    (radius 0 for the sphere), so d = d(circles) - r_a - r_b, with d(circles)
//    from the certified circle distance.
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "compare/brute_force.h"
#include "compare/circle_families.h"
#include "compare/random_geometry.h"
#include "compare/stress.h"
#include "core/case_io.h"
#include "exact/circle_distance_exact.h"

namespace revdist {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t case_seed(const std::string& family, long index, std::uint64_t seed) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a of the name: the same stream on every platform
  for (unsigned char ch : family) h = (h ^ ch) * 1099511628211ull;
  return mix(mix(seed ^ h) ^ static_cast<std::uint64_t>(index));
}

// Dyadic values (multiples of 2^-30) keep sums like R +- r exact.
double dyadic(double x) { return std::ldexp(std::round(std::ldexp(x, 30)), -30); }
double log_uniform(Rng& rng, double lo_exp, double hi_exp) { return std::pow(10.0, rng.uniform(lo_exp, hi_exp)); }

Piece line(Vec2 a, Vec2 b) {
  Piece p;
  p.points = {a, b};
  return p;
}
Piece arc(Vec2 a, Vec2 m, Vec2 b) {
  Piece p;
  p.kind = PieceKind::arc;
  p.degree = 2;
  p.points = {a, m, b};
  return p;
}
Piece bezier(std::vector<Vec2> pts) {
  Piece p;
  p.kind = PieceKind::bezier;
  p.degree = static_cast<int>(pts.size()) - 1;
  p.points = std::move(pts);
  return p;
}

Profile make_profile(std::vector<Piece> pieces, bool loop = false) {
  Profile p;
  p.pieces = std::move(pieces);
  p.closed_loop = loop;
  return p;
}

Profile sphere(double s) { return make_profile({arc({0, -s}, {s, 0}, {0, s})}); }
// A can of radius r, height h; `flare` widens the top so the side is a cone nearly parallel to the axis.
Profile can(double r, double h, double flare = 0) {
  return make_profile({line({0, 0}, {r, 0}), line({r, 0}, {r + flare, h}), line({r + flare, h}, {0, h})});
}
Profile cone(double r, double h) { return make_profile({line({0, 0}, {r, 0}), line({r, 0}, {0, h})}); }
Profile ring(double R, double r) {
  return make_profile({arc({R - r, 0}, {R, -r}, {R + r, 0}), arc({R + r, 0}, {R, r}, {R - r, 0})}, true);
}
// The part with r >= 0 of a circle of radius s centred at (c, 0), |c| < s: c > 0
// an apple (outer spindle torus), c < 0 a lemon, c = 0 a sphere; the poles are cusps.
Profile spindle(double c, double s) {
  const double w = std::sqrt(s * s - c * c);
  return make_profile({arc({0, -w}, {c + s, 0}, {0, w})});
}
// A vase: one cubic B-spline from the bottom pole to the top pole, control
// points rising in z (so the curve cannot cross itself), flat at both poles.
Profile vase(Rng& rng, double h = 1.5) {
  Piece p;
  p.kind = PieceKind::bspline;
  p.degree = 3;
  p.points = {{0, 0}, {rng.uniform(0.3, 0.8), 0}};
  for (int k = 1; k <= 3; ++k) p.points.push_back({rng.uniform(0.2, 1.0), h * k / 4});
  p.points.push_back({rng.uniform(0.2, 0.7), h});
  p.points.push_back({0, h});
  p.knots = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
  Profile out;
  out.pieces = {p};
  return out;
}
// A profile whose side is an S curve with a flat inflection: bulge a -> 0 makes it nearly straight.
Profile s_profile(double a) {
  return make_profile({line({0, 0}, {0.6, 0}), bezier({{0.6, 0}, {0.6 + a, 1.0 / 3}, {0.6 - a, 2.0 / 3}, {0.6, 1}}),
                       line({0.6, 1}, {0, 1})});
}

Profile scaled(Profile p, double f) {
  for (Piece& piece : p.pieces)
    for (Vec2& q : piece.points) q *= f;
  return p;
}

std::array<double, 4> quat_of(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }
std::array<double, 4> random_quat(Rng& rng) {
  return quat_of(Eigen::Quaterniond(Eigen::Vector4d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1),
                                                    rng.uniform(-1, 1)).normalized()));
}
// Local direction: the axis tilted by `tilt` radians toward a random side.
Vec3 tilted_axis(Rng& rng, double tilt, double sign = 1) {
  const double phi = rng.uniform(0, 2 * M_PI);
  return Vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), sign * std::cos(tilt));
}

StressCase two_solids(const std::vector<Profile>& keyframes_a, const std::vector<Profile>& keyframes_b, const Pose& pa,
                      const Pose& pb, double time) {
  StressCase c;
  c.solids.file = "<stress>";
  c.solids.solids = {{"a", keyframes_a}, {"b", keyframes_b}};
  c.solids.instances = {{"a", 0, pa, time, {}}, {"b", 1, pb, time, {}}};
  c.solids.queries = {{0, 1}};
  return c;
}

// Mirror pair of the solid (keyframes blended at `time`) at pose (q, t): the
// plane's normal is R_A n_local, its offset puts the mirror image at gap delta
// (negative: overlapping by -delta). expected = max(0, 2 (c - h_A)).
StressCase mirror_pair(const std::vector<Profile>& keyframes, double time, const std::array<double, 4>& q,
                       const Vec3& t, const Vec3& n_local, double delta) {
  Pose pa;
  pa.q = q;
  pa.translation = t;
  const Mat3 RA = pa.rotation();
  const Vec3 n = (RA * n_local.normalized()).normalized();
  SolidDef def{"s", keyframes};
  const Profile prof = profile_at(def, time);
  const double h = n.dot(t) + profile_support(prof, RA.transpose() * n);
  const double c = h + 0.5 * delta;
  const Mat3 M = Mat3::Identity() - 2 * n * n.transpose();
  const Mat3 F = Vec3(1, -1, 1).asDiagonal();
  Pose pb;
  pb.q = quat_of(Eigen::Quaterniond(Mat3(M * RA * F)));
  pb.translation = M * t + 2 * c * n;
  StressCase out = two_solids(keyframes, keyframes, pa, pb, time);
  out.expected = std::max(0.0, 2 * (c - h));
  return out;
}

StressCase mirror_pair(const Profile& p, Rng& rng, const Vec3& n_local, double delta, double translation = 1) {
  return mirror_pair({p}, 0.0, random_quat(rng), rng.box(translation), n_local, delta);
}

// A solid from the zoo, size about 1.
Profile any_solid(Rng& rng, std::string* what) {
  switch (static_cast<int>(rng.uniform(0, 7))) {
    case 0: *what = "sphere"; return sphere(dyadic(rng.uniform(0.3, 1)));
    case 1: *what = "can"; return can(rng.uniform(0.2, 1), rng.uniform(0.2, 1.5));
    case 2: *what = "cone"; return cone(rng.uniform(0.2, 1), rng.uniform(0.2, 1.5));
    case 3: *what = "ring"; return ring(dyadic(rng.uniform(0.5, 1)), dyadic(rng.uniform(0.05, 0.4)));
    case 4: *what = "spindle"; return spindle(rng.uniform(-0.5, 0.5), 0.8);
    case 5: *what = "s_profile"; return s_profile(rng.uniform(-0.2, 0.2));
    default: *what = "vase"; return vase(rng);
  }
}

// Tube pair: circle ca with tube radius ra (0: a point, then a sphere), same for b.
StressCase tube_pair(const Circle3& ca, double ra, const Circle3& cb, double rb) {
  auto solid_of = [](const Circle3& c, double r, Pose* p) {
    // Local z along the normal, centre at the origin: the profile is a ring or a sphere.
    p->q = quat_of(Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), c.normal.normalized()));
    p->translation = c.center;
    return c.radius > 0 ? ring(c.radius, r) : sphere(r);
  };
  Pose pa, pb;
  const Profile a = solid_of(ca, ra, &pa), b = solid_of(cb, rb, &pb);
  StressCase out = two_solids({a}, {b}, pa, pb, 0.0);
  // The circles the solids really have: the poses as the engines read them.
  const Circle3 ma{pa.translation, pa.rotation().col(2), ca.radius}, mb{pb.translation, pb.rotation().col(2), cb.radius};
  const ExactCircleResult x = circle3_circle3_distance_exact(ma, mb);
  out.expected = x.status == ExactStatus::not_certified ? kNaN : std::max(0.0, 0.5 * (x.lower + x.upper) - ra - rb);
  return out;
}

using Maker = StressCase (*)(Rng&, long);

StressCase near_coaxial(Rng& rng, long i) {
  std::string what;
  Profile p = i % 3 == 0 ? ring(0.75, dyadic(rng.uniform(0.05, 0.3))) : i % 3 == 1 ? vase(rng) : sphere(0.5);
  StressCase c = mirror_pair(p, rng, tilted_axis(rng, log_uniform(rng, -12, -3)), log_uniform(rng, -9, -1));
  c.note = "mirror across a plane whose normal is the axis tilted 1e-12..1e-3 (ring / vase / sphere)";
  return c;
}

StressCase near_parallel_planes(Rng& rng, long i) {
  const double r = rng.uniform(0.3, 1);
  Profile p = i % 2 ? can(r, rng.uniform(0.1, 1)) : can(r, r * log_uniform(rng, -4, -1));
  StressCase c = mirror_pair(p, rng, tilted_axis(rng, log_uniform(rng, -12, -3), i % 4 < 2 ? 1 : -1),
                             log_uniform(rng, -9, -1));
  c.note = "flat faces of cans and coins facing each other, tilted 1e-12..1e-3";
  return c;
}

StressCase tangent_touching(Rng& rng, long i) {
  std::string what;
  const Profile p = any_solid(rng, &what);
  const double delta = i % 3 == 0 ? 0.0 : (i % 3 == 1 ? 1 : -1) * log_uniform(rng, -15, -12);
  StressCase c = mirror_pair(p, rng, rng.unit(), delta);
  c.note = what + " touching its mirror image (gap 0 or +-1e-15..1e-12)";
  return c;
}

StressCase interlocked_rings(Rng& rng, long) {
  // Ring a: major radius 1 about z. Ring b threads a's hole: its centre near a
  // point of a's major circle, its plane nearly containing a's axis direction.
  const double phi = rng.uniform(0, 2 * M_PI);
  const Vec3 p(std::cos(phi), std::sin(phi), 0), tang(-std::sin(phi), std::cos(phi), 0);
  const Circle3 ca{Vec3::Zero(), Vec3::UnitZ(), 1.0};
  const Vec3 nb = (tang + 0.3 * rng.box(1)).normalized();
  const Circle3 cb{p + 0.2 * rng.box(1), nb, dyadic(rng.uniform(0.6, 1.4))};
  const double dc = circle3_circle3_distance_exact(ca, cb).lower;
  const double ra = dyadic(rng.uniform(0.1, 0.6) * dc);
  // Below b's major radius, so b stays a ring (its loop must not reach its axis).
  const double rb = std::min(dyadic((dc - ra) * (1 - log_uniform(rng, -9, -0.5))), dyadic(0.9 * cb.radius));
  const Motion m = random_motion(rng, 1);
  StressCase c = tube_pair(m.apply(ca), ra, m.apply(cb), rb);
  c.note = "linked rings, tubes 1e-9..0.3 of the free gap apart";
  return c;
}

StressCase concentric(Rng& rng, long i) {
  // A ring around a sphere or a smaller ring, same centre, axes equal or tilted up to 1e-3.
  const double R = dyadic(rng.uniform(0.8, 1.2)), r = dyadic(rng.uniform(0.05, 0.2));
  const Vec3 axis = i % 2 ? Vec3::UnitZ() : tilted_axis(rng, log_uniform(rng, -12, -3));
  const Circle3 ca{Vec3::Zero(), Vec3::UnitZ(), R};
  const bool inner_sphere = i % 4 < 2;
  const Circle3 cb{Vec3::Zero(), axis, inner_sphere ? 0.0 : dyadic(rng.uniform(0.2, 0.5))};
  const double gap = R - r - cb.radius;
  const double rb = dyadic(gap * (inner_sphere ? 1 - log_uniform(rng, -9, -0.5) : rng.uniform(0.1, 0.5)));
  const Motion m = random_motion(rng, 1);
  StressCase c = tube_pair(m.apply(ca), r, m.apply(cb), inner_sphere ? rb : std::min(rb, cb.radius * 0.5));
  c.note = inner_sphere ? "ring around a concentric sphere" : "ring around a concentric smaller ring";
  return c;
}

StressCase points_poles(Rng& rng, long i) {
  // Tips meet tips: cones and lemons mirrored along (nearly) their axis.
  const Profile p = i % 2 ? cone(rng.uniform(0.2, 1), rng.uniform(0.3, 1.5)) : spindle(-rng.uniform(0.1, 0.6), 0.8);
  StressCase c = mirror_pair(p, rng, tilted_axis(rng, i % 4 < 2 ? 0.0 : log_uniform(rng, -8, -1)),
                             log_uniform(rng, -9, -1));
  c.note = "cone tips / lemon cusps facing each other along (nearly) the axis";
  return c;
}

StressCase axis_parallel_lines(Rng& rng, long i) {
  const double flare = i % 2 ? 0.0 : (i % 4 ? 1 : -1) * log_uniform(rng, -9, -3);
  const Profile p = can(rng.uniform(0.2, 0.8), rng.uniform(0.5, 2), flare);
  const double tilt = log_uniform(rng, -12, -3), phi = rng.uniform(0, 2 * M_PI);
  // The plane's normal nearly perpendicular to the axis: side by side, axes nearly parallel.
  const Vec3 n(std::cos(phi) * std::cos(tilt), std::sin(phi) * std::cos(tilt), std::sin(tilt));
  StressCase c = mirror_pair(p, rng, n, log_uniform(rng, -9, -1));
  c.note = "cylinders / cones flared 1e-9..1e-3 side by side, axes parallel within 1e-12..1e-3";
  return c;
}

StressCase thin_coins(Rng& rng, long) {
  const double r = rng.uniform(0.5, 1);
  StressCase c = mirror_pair(can(r, r * log_uniform(rng, -6, -2)), rng, rng.unit(), log_uniform(rng, -9, -1));
  c.note = "coins 1e-6..1e-2 thin, random mirror";
  return c;
}

StressCase spindle_sphere_tori(Rng& rng, long i) {
  const double s = 0.8, off = (i % 2 ? 1 : -1) * s * (i % 4 < 2 ? log_uniform(rng, -9, -3) : rng.uniform(0.05, 0.9));
  StressCase c = mirror_pair(spindle(off, s), rng, rng.unit(), log_uniform(rng, -9, -1));
  c.note = "apples and lemons (spindle tori) to 1e-9 from a sphere";
  return c;
}

StressCase near_inflection(Rng& rng, long i) {
  const double a = (i % 2 ? 1 : -1) * log_uniform(rng, -6, -1);
  const double phi = rng.uniform(0, 2 * M_PI), tilt = rng.uniform(-0.2, 0.2);
  StressCase c = mirror_pair(s_profile(a), rng, Vec3(std::cos(phi), std::sin(phi), std::sin(tilt)),
                             log_uniform(rng, -9, -1));
  c.note = "S-shaped sides (inflection, bulge 1e-6..0.1) facing each other";
  return c;
}

StressCase scale_family(Rng& rng, long) {
  std::string what;
  const double f = log_uniform(rng, -6, 6);
  const Profile p = scaled(any_solid(rng, &what), f);
  StressCase c = mirror_pair({p}, 0.0, random_quat(rng), f * rng.box(1), rng.unit(), f * log_uniform(rng, -9, -1));
  c.note = what + " scaled 1e-6..1e6";
  return c;
}

StressCase far_from_origin(Rng& rng, long) {
  std::string what;
  const Profile p = any_solid(rng, &what);
  StressCase c = mirror_pair({p}, 0.0, random_quat(rng), 1e6 * rng.unit() + rng.box(1), rng.unit(),
                             log_uniform(rng, -6, -1));
  c.note = what + " 1e6 from the origin";
  return c;
}

StressCase identical_tiny_gap(Rng& rng, long) {
  std::string what;
  const Profile p = any_solid(rng, &what);
  StressCase c = mirror_pair(p, rng, rng.unit(), log_uniform(rng, -9, -4));
  c.note = what + " and its mirror image 1e-9..1e-4 apart";
  return c;
}

StressCase slight_overlap(Rng& rng, long) {
  std::string what;
  const Profile p = any_solid(rng, &what);
  StressCase c = mirror_pair(p, rng, rng.unit(), -log_uniform(rng, -9, -2));
  c.note = what + " overlapping its mirror image by 1e-9..1e-2";
  return c;
}

StressCase containment(Rng& rng, long) {
  // A small solid (extent <= 0.25 from its origin) well inside a ball of radius 1.
  std::string what;
  const Profile small = scaled(any_solid(rng, &what), 0.15);
  Pose pa, pb;
  pa.q = random_quat(rng);
  pa.translation = rng.box(1);
  pb.q = random_quat(rng);
  pb.translation = pa.translation + 0.5 * rng.uniform(0, 1) * rng.unit();
  StressCase c = two_solids({sphere(1)}, {small}, pa, pb, 0.0);
  c.expected = 0;
  c.note = "a small " + what + " inside a ball (solid distance 0, surfaces apart)";
  return c;
}

StressCase deformable_blends(Rng& rng, long) {
  // Two keyframes of the same vase structure; the instance blends them at a random time.
  std::vector<Profile> keys = {vase(rng), vase(rng)};
  keys[1].pieces[0].knots = keys[0].pieces[0].knots;
  StressCase c = mirror_pair(keys, rng.uniform(0, 1), random_quat(rng), rng.box(1), rng.unit(),
                             log_uniform(rng, -9, -1));
  c.note = "a vase blended between two keyframes, mirrored";
  return c;
}

struct SolidEntry {
  const char* name;
  const char* description;
  Maker make;
};

const std::vector<SolidEntry>& solid_entries() {
  static const std::vector<SolidEntry> all = {
      {"near_coaxial", "rings, vases, spheres stacked on (nearly) one axis", near_coaxial},
      {"near_parallel_planes", "flat faces of cans and coins, tilted 1e-12..1e-3", near_parallel_planes},
      {"tangent_touching", "solids touching their mirror image (gap 0, +-1e-15..1e-12)", tangent_touching},
      {"interlocked_rings", "linked rings near contact", interlocked_rings},
      {"concentric", "rings around concentric spheres and rings", concentric},
      {"points_poles", "cone tips and lemon cusps tip to tip", points_poles},
      {"axis_parallel_lines", "cylinders and near-cylinders side by side", axis_parallel_lines},
      {"thin_coins", "coins 1e-6..1e-2 thin", thin_coins},
      {"spindle_sphere_tori", "apples and lemons near a sphere", spindle_sphere_tori},
      {"near_inflection", "S-shaped sides with a flat inflection", near_inflection},
      {"scale", "every shape at scales 1e-6..1e6", scale_family},
      {"far_from_origin", "every shape 1e6 from the origin", far_from_origin},
      {"identical_tiny_gap", "a solid and its mirror image 1e-9..1e-4 apart", identical_tiny_gap},
      {"slight_overlap", "a solid overlapping its mirror image by 1e-9..1e-2", slight_overlap},
      {"containment", "a small solid inside a ball", containment},
      {"deformable_blends", "keyframed vases at random times, mirrored", deformable_blends},
  };
  return all;
}

}  // namespace

const std::vector<FamilyInfo>& stress_families() {
  static const std::vector<FamilyInfo> all = [] {
    std::vector<FamilyInfo> v;
    for (const CircleFamily& f : circle_families()) v.push_back({"circle_" + f.name, true, f.description});
    for (const SolidEntry& e : solid_entries()) v.push_back({e.name, false, e.description});
    return v;
  }();
  return all;
}

StressCase make_stress_case(const std::string& family, long index, std::uint64_t seed) {
  const std::uint64_t s = case_seed(family, index, seed);
  if (family.rfind("circle_", 0) == 0) {
    const CircleFamilyPair p = make_circle_family_pair(family.substr(7), index, s);
    StressCase c;
    c.is_circle = true;
    c.a = p.pair.a;
    c.b = p.pair.b;
    c.expected = p.expected;
    c.family = family;
    c.index = index;
    return c;
  }
  for (const SolidEntry& e : solid_entries()) {
    if (family != e.name) continue;
    Rng rng(s);
    StressCase c = e.make(rng, index);
    c.family = family;
    c.index = index;
    return c;
  }
  throw std::invalid_argument("unknown stress family \"" + family + "\"");
}

}  // namespace revdist
