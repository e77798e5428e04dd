// Tests of the hull bound for conical patches (fast/cone_hull.h): exact on
// closed forms (parallel and skew cylinders side by side), never above a
// genuine pair of patch points, and what makes near-parallel cans cheap
// (the regression case and a stretch of the axis_parallel_lines family).
#include "fast/cone_hull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "compare/stress.h"
#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/patch_distance.h"
#include "fast/solid_distance.h"
#include "tests/fast/biarc_test_util.h"

namespace revdist {
namespace {

using testing_util::test_seed;

constexpr double kE = 2.220446049250313e-16;

Arc2 segment(const Vec2& p0, const Vec2& p1) {
  Arc2 a;
  a.start = p0;
  a.tangent = (p1 - p0).normalized();
  a.curvature = 0.0;
  a.length = (p1 - p0).norm();
  return a;
}

Mat3 rotation(double angle, const Vec3& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

// Is x on straight patch P (its cone line within tol, inside the segment)?
bool on_patch(const Patch& P, const Vec3& x, double tol) { return patch_contains_local(P, patch_local(P, x), tol); }

// Two cylinders of radii r1, r2, axes along R z through R (0,0,0) and R (D, 0, 0)
// tilted by gamma about the x axis (the common perpendicular is the x axis,
// both feet at height 0 inside both segments): distance D - r1 - r2.
TEST(ConeHull, SkewCylindersClosedForm) {
  std::mt19937_64 g(test_seed(5));
  std::uniform_real_distribution<double> u(0, 1);
  // The bound's loss against the closed form: measured worst 1.9e-9 (axes
  // ~1e-8 rad apart, gap 8e-9: the separating direction is solved in doubles
  // from witnesses placed to ~sqrt(eps) along the generators); 4x margin.
  // The witnesses' excess (upper - gap, up to 1.4e-8 measured) is only
  // reported: an upper bound needs genuine points, not the closest ones.
  constexpr double kLoss = 8e-9;
  int tight = 0;
  double worst_loss = 0, worst_upper = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double r1 = 0.2 + u(g), r2 = 0.2 + u(g);
    const double gap = std::pow(10.0, -9 + 8 * u(g));
    const double D = r1 + r2 + gap;
    const double gamma = trial % 4 == 0 ? 0.0 : std::pow(10.0, -12 + 10 * u(g));
    const Mat3 R = rotation(2 * M_PI * u(g), Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5));
    const Vec3 t(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5);
    const Patch A = make_patch(segment({r1, -1.0 - u(g)}, {r1, 1.0 + u(g)}), R, t);
    const Patch B = make_patch(segment({r2, -1.0 - u(g)}, {r2, 1.0 + u(g)}), R * rotation(gamma, Vec3::UnitX()),
                               R * Vec3(D, 0, 0) + t);
    const ConeHullResult h = cone_hull_distance(A, B);
    // Rounding: the rotation and translation move the axes by a few ulps of
    // the coordinates (~3), the bound carries its own allowance: 256 ulps.
    const double allow = 256 * kE * 4;
    SCOPED_TRACE("trial " + std::to_string(trial) + " gap " + std::to_string(gap) + " gamma " + std::to_string(gamma));
    EXPECT_LE(h.lower, gap + allow);
    // Exact but for the separating direction and the witnesses' place along
    // the generators, both solved in doubles: measured worst loss below.
    worst_loss = std::max(worst_loss, gap - h.lower);
    worst_upper = std::max(worst_upper, h.upper - gap);
    EXPECT_GE(h.lower, gap - kLoss) << "the bound is exact for cylinders side by side";
    EXPECT_LE(h.lower, h.upper);
    EXPECT_GE(h.upper, gap - allow);
    // The witnesses are genuine points of the patches (to their rounding).
    EXPECT_TRUE(on_patch(A, h.x, 64 * kE * 4));
    EXPECT_TRUE(on_patch(B, h.y, 64 * kE * 4));
    tight += h.upper - h.lower <= allow;
  }
  std::printf("[ stats    ] %d of 200 exact to rounding; worst loss %.3g, upper excess %.3g\n", tight, worst_loss,
              worst_upper);
}

// Random near-parallel cone pairs (flares 1e-9..1e-2, axes parallel within
// 1e-12..1e-2, side by side, stacked or crossing): the bound never exceeds a
// genuine pair, neither the hull's own witnesses nor the enumeration's best
// candidate nor any pair of a sample grid of both patches.
TEST(ConeHull, NeverAboveAGenuinePair) {
  std::mt19937_64 g(test_seed(6));
  std::uniform_real_distribution<double> u(0, 1);
  int proven = 0;
  for (int trial = 0; trial < 300; ++trial) {
    auto cone = [&](double r) {
      const double z0 = -u(g), z1 = z0 + 0.1 + u(g);
      const double flare = (u(g) < 0.5 ? -1 : 1) * std::pow(10.0, -9 + 7 * u(g));
      return segment({r, z0}, {std::max(r + flare * (z1 - z0), 0.0), z1});
    };
    const double r1 = 0.1 + u(g), r2 = 0.1 + u(g);
    const Mat3 R = rotation(2 * M_PI * u(g), Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5));
    const double tilt = std::pow(10.0, -12 + 10 * u(g));
    const int kind = trial % 3;  // side by side, stacked, crossing
    const Vec3 off = kind == 0 ? Vec3(r1 + r2 + std::pow(10.0, -8 + 7 * u(g)), 0, u(g) - 0.5)
                     : kind == 1 ? Vec3(0.1 * u(g), 0, 2.5)
                                 : Vec3(0.5 * (r1 + r2), 0, 0.3 * u(g));
    const Patch A = make_patch(cone(r1), R, Vec3::Zero());
    const Patch B = make_patch(cone(r2), R * rotation(tilt, Vec3(u(g) - 0.5, u(g) - 0.5, 0)), R * off);
    const ConeHullResult h = cone_hull_distance(A, B);
    SCOPED_TRACE("trial " + std::to_string(trial));
    if (!(h.lower > 0)) continue;
    ++proven;
    // Rounding of the candidates' coordinates (all within ~4 of the origin): 64 ulps.
    const double allow = 64 * kE * 4;
    EXPECT_LE(h.lower, h.upper + allow);
    EXPECT_TRUE(on_patch(A, h.x, 1e-12));
    EXPECT_TRUE(on_patch(B, h.y, 1e-12));
    const PatchPairResult p = patch_pair_distance(A, B);
    if (p.found) { EXPECT_LE(h.lower, p.upper + allow); }
    double sampled = std::numeric_limits<double>::infinity();
    constexpr int kU = 8, kT = 32;
    auto point = [](const Patch& P, int i, int j) {
      const Vec2 q = P.p0 + (P.p1 - P.p0) * (double(i) / (kU - 1));
      const Vec3 e1 = P.a.unitOrthogonal(), e2 = P.a.cross(e1);
      const double th = 2 * M_PI * j / kT;
      return Vec3(P.o + q.x() * (std::cos(th) * e1 + std::sin(th) * e2) + q.y() * P.a);
    };
    for (int i = 0; i < kU; ++i)
      for (int j = 0; j < kT; ++j)
        for (int k = 0; k < kU; ++k)
          for (int l = 0; l < kT; ++l) sampled = std::min(sampled, (point(A, i, j) - point(B, k, l)).norm());
    EXPECT_LE(h.lower, sampled + allow);
  }
  std::printf("[ stats    ] %d of 300 pairs proven apart by their hulls\n", proven);
  EXPECT_GE(proven, 100);  // every side-by-side pair at least
}

// The closest pair of two grids of kU profile fractions (0..1) by kT
// azimuths on surfaces a(t, th) and b(t, th): its distance, the parameters of
// its point on a, and both points.
struct GridPair {
  double dist = std::numeric_limits<double>::infinity();
  Vec2 a_param = Vec2::Zero();
  Vec3 x = Vec3::Zero(), y = Vec3::Zero();
};
template <class SurfA, class SurfB>
GridPair closest_grid_pair(SurfA a, SurfB b, int kU, int kT) {
  std::vector<Vec3> pb;
  for (int k = 0; k < kU; ++k)
    for (int l = 0; l < kT; ++l) pb.push_back(b(double(k) / (kU - 1), 2 * M_PI * l / kT));
  GridPair best;
  for (int i = 0; i < kU; ++i)
    for (int j = 0; j < kT; ++j) {
      const Vec2 param(double(i) / (kU - 1), 2 * M_PI * j / kT);
      const Vec3 x = a(param.x(), param.y());
      for (const Vec3& y : pb)
        if ((x - y).norm() < best.dist) best = {(x - y).norm(), param, x, y};
    }
  return best;
}

// A hull bound along the closest pair's direction and five random ones, with
// 0 and 2 refining steps, never above `limit` (a genuine pair's distance).
template <class Bound>
void expect_never_above(Bound bound, const Vec3& closest, double limit, std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(0, 1);
  for (int d = 0; d < 6; ++d) {
    const Vec3 dir = d == 0 ? closest : Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5);
    for (int steps : {0, 2}) EXPECT_LE(bound(dir, steps), limit) << "direction " << d << ", steps " << steps;
  }
}

// patch_hull_bound on random toroidal and conical patches (arcs up to a
// half turn, either side bulging towards the other patch, some of A's on a
// sphere from its pole) near each other:
// along any direction it never exceeds a genuine pair's distance (the best
// of a sample grid, descended to a local minimum of both patches), and along
// the sampled closest pair's direction it proves most pairs side by side
// apart, often to within a tenth of their distance.
TEST(PatchHullBound, NeverAboveTheDistanceOfToriAndCones) {
  std::mt19937_64 g(test_seed(7));
  std::uniform_real_distribution<double> u(0, 1);
  auto random_arc = [&](bool straight) {
    Arc2 a;
    a.start = Vec2(0.2 + u(g), u(g) - 0.5);
    const double phi = 2 * M_PI * u(g);
    a.tangent = Vec2(std::cos(phi), std::sin(phi));
    a.curvature = straight ? 0.0 : (u(g) < 0.5 ? -1 : 1) * (0.5 + 4.5 * u(g));
    a.length = straight ? 0.05 + 0.5 * u(g) : (0.02 + 0.98 * u(g)) * M_PI / std::abs(a.curvature);
    // Keep the arc off the axis (r >= 0 throughout): shift it out.
    double rmin = a.start.x();
    for (int k = 1; k <= 32; ++k) rmin = std::min(rmin, a.point(a.length * k / 32).x());
    if (rmin < 0.05) a.start.x() += 0.05 - rmin;
    return a;
  };
  // An arc of a sphere about the axis from its pole, up to the other pole.
  auto sphere_arc = [&] {
    Arc2 a;
    const double R = 0.1 + 0.9 * u(g);
    a.start = Vec2(0.0, u(g) - 0.5 - R);
    a.tangent = Vec2(1, 0);
    a.curvature = 1 / R;
    a.length = (0.05 + 0.95 * u(g)) * M_PI * R;
    return a;
  };
  int proven = 0, tight = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Patch A = make_patch(trial % 5 == 4 ? sphere_arc() : random_arc(trial % 3 == 0), Mat3::Identity(), Vec3::Zero());
    const Mat3 R = rotation(2 * M_PI * u(g), Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5));
    const Vec3 t = 2.5 * Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5);
    const Patch B = make_patch(random_arc(trial % 3 == 1), R, t);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // The closest pair of a grid, descended: genuine points of both patches.
    const GridPair grid = closest_grid_pair([&](double t, double th) { return patch_point(A, t, th); },
                                            [&](double t, double th) { return patch_point(B, t, th); }, 12, 32);
    Vec3 x, y;
    const double genuine = std::min(grid.dist, patch_pair_descent(A, B, grid.a_param, 1e-12, &x, &y));
    // Coordinates within ~3 of the origin: 256 ulps of them.
    const double allow = 256 * kE * 4;
    expect_never_above([&](const Vec3& dir, int steps) { return patch_hull_bound(A, B, dir, steps); }, x - y,
                       genuine + allow, g);
    const double along = patch_hull_bound(A, B, x - y, 1);
    // The query's form, its direction prepared once for the two axes, is
    // the same bound bit for bit.
    const RevolvedHullDirection h(A.o, A.a, B.o, B.a, x - y);
    EXPECT_EQ(h.patches(A, B), patch_hull_bound(A, B, x - y, 0));
    proven += along > 0;
    tight += along >= 0.9 * genuine;
  }
  std::printf("[ stats    ] of 300 pairs: %d proven apart along the closest pair's direction, %d to 10 %%\n", proven,
              tight);
  // Measured at the default seed: 151 and 117 (seeds 1-80: at least 129 and
  // 93; the chord cones less the sagittas gave 115 and 34).
  EXPECT_GE(proven, 100);
  EXPECT_GE(tight, 60);
}

// revolved_hull_bound on random segments revolved about random axes, some
// crossing their axis (the hull then takes |r|): along any direction it never
// exceeds the distance of a sample grid of both revolved segments, and along
// the grid's closest pair it proves most pairs apart.
TEST(RevolvedHullBound, NeverAboveSampledPairs) {
  std::mt19937_64 g(test_seed(8));
  std::uniform_real_distribution<double> u(0, 1);
  auto random_segment = [&](const Vec3& o, const Vec3& a) {
    const Vec2 p0(u(g) - 0.2, u(g) - 0.5);
    const Vec2 p1 = p0 + 0.6 * Vec2(u(g) - 0.5, u(g) - 0.5);
    return RevolvedSegment{o, a, p0, p1};
  };
  auto point = [](const RevolvedSegment& s, double t, double th) {
    const Vec3 e1 = s.a.unitOrthogonal(), e2 = s.a.cross(e1);
    const Vec2 q = s.p0 + t * (s.p1 - s.p0);
    return Vec3(s.o + q.x() * (std::cos(th) * e1 + std::sin(th) * e2) + q.y() * s.a);
  };
  int proven = 0, crossing = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const RevolvedSegment A = random_segment(Vec3::Zero(), Vec3::UnitZ());
    const Vec3 ab = Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5).normalized();
    const RevolvedSegment B = random_segment(2.0 * Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5), ab);
    crossing += (A.p0.x() < 0) != (A.p1.x() < 0);
    const GridPair grid = closest_grid_pair([&](double t, double th) { return point(A, t, th); },
                                            [&](double t, double th) { return point(B, t, th); }, 16, 48);
    SCOPED_TRACE("trial " + std::to_string(trial));
    const double allow = 256 * kE * 4;
    expect_never_above([&](const Vec3& dir, int steps) { return revolved_hull_bound(A, B, dir, steps); },
                       grid.x - grid.y, grid.dist + allow, g);
    proven += revolved_hull_bound(A, B, grid.x - grid.y, 0) > 0;
  }
  std::printf("[ stats    ] of 300 pairs (%d crossing their axis): %d proven apart along the closest pair\n", crossing,
              proven);
  EXPECT_GE(crossing, 30);
  EXPECT_GE(proven, 100);
}

// Flat faces facing each other along their common axis, gap 1e-9..1e-3, the
// direction along the axis to within 1e-12..1e-6 and tiny: the bound never
// exceeds the gap (the stress near_parallel_planes regression: |u_perp|
// taken as sqrt(|u|^2 - (u . a)^2) lost sqrt(eps) of |u|, times the radius),
// and it is the gap to within a few ulps of the radius.
TEST(RevolvedHullBound, FlatFacesAlongTheAxis) {
  std::mt19937_64 g(test_seed(9));
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const double r = 0.1 + u(g), gap = std::pow(10.0, -9 + 6 * u(g));
    const Vec3 axis = Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5).normalized();
    const Vec3 o = Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5);
    // B's face is A's, lifted by the gap and shifted sideways (still overlapping).
    const Vec3 side = 0.3 * r * u(g) * axis.unitOrthogonal();
    const RevolvedSegment A{o, axis, Vec2(0, 0), Vec2(r, 0)};
    const RevolvedSegment B{o + gap * axis + side, axis, Vec2(0, 0), Vec2(r, 0)};
    const Vec3 tilt = std::pow(10.0, -12 + 6 * u(g)) * Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5);
    const Vec3 dir = std::pow(10.0, -12 + 10 * u(g)) * (-axis + tilt);  // from B towards A
    SCOPED_TRACE("trial " + std::to_string(trial) + " gap " + std::to_string(gap));
    const double allow = 64 * kE * 2;
    for (int steps : {0, 1}) {
      const double b = revolved_hull_bound(A, B, dir, steps);
      EXPECT_LE(b, gap + allow);
      EXPECT_GE(b, gap - 2e-6 * r - allow);  // the tilt costs at most |tilt| r on each face
    }
  }
}

// Any positive multiple of a direction gives the same bound, also one that
// squares into the subnormals (a witness pair 1e-160 apart) or overflows.
TEST(RevolvedHullBound, ScaleOfTheDirection) {
  std::mt19937_64 g(test_seed(10));
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const RevolvedSegment A{Vec3::Zero(), Vec3::UnitZ(), Vec2(0.5 * u(g), u(g)), Vec2(0.5 * u(g), 1 + u(g))};
    const Vec3 b_axis = Vec3(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5).normalized();
    const RevolvedSegment B{Vec3(2 + u(g), u(g), u(g)), b_axis, Vec2(0.3 * u(g), -u(g)), Vec2(0.3 * u(g), u(g))};
    // Components with a largest magnitude in [0.5, 1): the scaled ones map back exactly.
    const Vec3 d = Vec3(-0.5 - 0.49 * u(g), 0.4 * (u(g) - 0.5), 0.4 * (u(g) - 0.5));
    const double ref = revolved_hull_bound(A, B, d, 0);
    ASSERT_TRUE(std::isfinite(ref));
    for (int e : {-1070, -600, -520, 520, 600, 1000}) {
      const Vec3 s(std::ldexp(d.x(), e), std::ldexp(d.y(), e), std::ldexp(d.z(), e));
      // The direction s represents (exact: at 2^-1070 the subnormals keep
      // only some of d's digits, a nearby direction).
      const Vec3 back(std::ldexp(s.x(), -e), std::ldexp(s.y(), -e), std::ldexp(s.z(), -e));
      EXPECT_EQ(revolved_hull_bound(A, B, s, 0), revolved_hull_bound(A, B, back, 0)) << "2^" << e;
      if (e > -1060) { EXPECT_EQ(revolved_hull_bound(A, B, s, 0), ref) << "2^" << e; }
    }
    // A plain multiple (not a power of two) agrees to rounding.
    EXPECT_NEAR(revolved_hull_bound(A, B, 1e-160 * d, 0), ref, 1e-14);
  }
}

// The regression: cans 5.6e-5 rad from parallel needed minutes (every patch
// pair's normal system overflowed, no pair was ever proven apart). With a
// budget of 20,000 node pairs the old engine ends unconverged; measured now:
// 175 node pairs at eps 1e-5 of the size.
TEST(ConeHull, NearParallelCansConvergeWithLittleWork) {
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/regressions/solid_near_parallel_cones.json");
  const double expected = 0.003276465541937279;
  const CaseModel m = build_case_model(c, 1e-5 * 2.1);
  DistanceOptions o;
  o.tol = 1e-9;
  o.max_node_pairs = 20000;
  const SolidDistanceResult r = solid_distance(m.instances[0], m.instances[1], o);
  std::printf("[ query    ] [%.17g, %.17g] %ld node pairs, %ld patch pairs\n", r.lower, r.upper, r.stats.node_pairs,
              r.stats.patch_pairs);
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_LE(r.stats.node_pairs, 2000);
  // The closed form of the mirror construction, to its rounding (coordinates ~2).
  EXPECT_LE(r.lower, expected + 1e-12);
  EXPECT_GE(r.upper, expected - 1e-12);
}

// A stretch of `revdist stress --family axis_parallel_lines --seed 7` (cylinders
// and cones flared 1e-9..1e-3, axes parallel within 1e-12..1e-3): every query
// converges within a small budget and holds the construction's distance.
TEST(ConeHull, AxisParallelFamilyConvergesCheaply) {
  long worst = 0;
  for (long i = 0; i < 100; ++i) {
    const StressCase sc = make_stress_case("axis_parallel_lines", i, 7);
    const CaseModel m = build_case_model(sc.solids, 1e-5 * 2.1);
    DistanceOptions o;
    o.tol = 1e-6 * 2.1;
    o.max_node_pairs = 20000;
    const SolidDistanceResult r = solid_distance(m.instances[0], m.instances[1], o);
    SCOPED_TRACE("case " + std::to_string(i) + ": " + sc.note);
    EXPECT_TRUE(r.converged) << r.reason;
    // Coordinates up to ~4: 1e-12 covers the construction's and the bounds' rounding.
    EXPECT_LE(r.lower, sc.expected + 1e-12);
    EXPECT_GE(r.upper, sc.expected - 1e-12);
    worst = std::max(worst, r.stats.node_pairs);
  }
  std::printf("[ stats    ] axis_parallel_lines 0..99: at most %ld node pairs\n", worst);
  EXPECT_LE(worst, 5000);
}

}  // namespace
}  // namespace revdist
