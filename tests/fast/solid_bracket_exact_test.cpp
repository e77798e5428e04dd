// Brackets against exact arithmetic, not decimals (issue 10 item 16): the
// distance of two balls of the given doubles, r1 + r2 subtracted from the
// centre distance along an axis, is exact in binary128 (the doubles' exponents
// are close), so lower <= d <= upper is checked without rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist {
namespace {

using Quad = __float128;

// Balls of radius r at the origin and at t along an axis, for several scales:
// the exact distance t - 2r of the doubles t and r.
TEST(SolidBracketExact, BallsAlongAnAxisHoldTheExactDistance) {
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/regressions/upper_rounded_outward_balls.json");
  const double r = 0.01;
  std::vector<double> seps = {0.03, 0.0300000000000001, 0.021, 0.02000001, 0.5, 3.3};
  // And separations of full mantissas over the same range, along each axis
  // (fixed seed: the exact check needs no other). (Since the first witness is
  // polished, none of these needs the lower bounds' rounding allowance to
  // hold: the no_rounding mutant survives this test and the stacked coins';
  // the tilted coins' below catch it.)
  std::mt19937_64 g(20261127);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 60; ++k) seps.push_back(0.0201 * std::pow(3.3 / 0.0201, U(g)));
  const CaseModel m = build_case_model(c, 1e-5);
  for (std::size_t k = 0; k < seps.size(); ++k) {
    PosedSolid a = m.instances[0], b = m.instances[1];
    // Every third pair far from the origin, where the coordinates' rounding
    // (not the distance's) is what the allowance must cover.
    a.t = k % 3 == 2 ? Vec3(700 + 600 * U(g), -900 * U(g), 300 * U(g)) : Vec3::Zero();
    b.t = a.t;
    b.t[k % 3] += seps[k];
    const double t = b.t[k % 3] - a.t[k % 3];  // the doubles' separation, exact (Sterbenz)
    // (Far from the origin tol 1e-12 is below the coordinates' rounding: 1e-9 there.)
    for (const double tol : {1e-6, k % 3 == 2 ? 1e-9 : 1e-12}) {
      DistanceOptions o;
      o.tol = tol;
      const SolidDistanceResult res = solid_distance(a, b, o);
      const Quad d = static_cast<Quad>(b.t[k % 3]) - static_cast<Quad>(a.t[k % 3]) - 2 * static_cast<Quad>(r);
      EXPECT_TRUE(static_cast<Quad>(res.lower) <= d) << "t " << t << " tol " << tol << ": lower above the exact distance";
      EXPECT_TRUE(d <= static_cast<Quad>(res.upper)) << "t " << t << " tol " << tol << " upper " << res.upper
                                                    << " below the exact distance";
      EXPECT_TRUE(res.converged) << res.reason;
      EXPECT_LE(res.upper - res.lower, tol);
    }
  }
}

// The two coins of cases/regressions/rounding_stacked_coins.json (radius
// 0.5, kCoinHeight thick, faces of exact lines), fitted at eps 1e-5.
constexpr double kCoinHeight = 0.1;
CaseModel coins() {
  return build_case_model(
      read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/regressions/rounding_stacked_coins.json"), 1e-5);
}

// Coins stacked on one axis (z), 10 to 1e6 from the origin: their flat faces
// are parallel, the closest pairs a whole disk, and the bracket settles within
// a few hundred ulps of the coordinates around the gap, where only the
// rounding allowances keep it honest (the faces' heights are computed from
// rounded coordinates). The exact distance is b.z - a.z - h of the given
// doubles, in binary128.
TEST(SolidBracketExact, StackedCoinsFarOffHoldTheExactGap) {
  const double h = kCoinHeight;
  const CaseModel m = coins();
  std::mt19937_64 g(20261128);
  std::uniform_real_distribution<double> U(0, 1);
  int tight = 0;
  for (int k = 0; k < 200; ++k) {
    PosedSolid a = m.instances[0], b = m.instances[1];
    const double far = std::pow(10.0, 1 + 5 * U(g));  // 10 to 1e6 from the origin
    a.t = Vec3(far * (U(g) - 0.5), far * (U(g) - 0.5), far * (U(g) - 0.5));
    b.t = a.t;
    b.t.z() += h + 1e-3 * std::pow(1e3, U(g));  // gaps 1e-3 to 1
    const Quad d = static_cast<Quad>(b.t.z()) - static_cast<Quad>(a.t.z()) - static_cast<Quad>(h);
    for (const double tol : {1e-6, 1e-12 * far}) {
      DistanceOptions o;
      o.tol = tol;
      const SolidDistanceResult res = solid_distance(a, b, o);
      EXPECT_TRUE(static_cast<Quad>(res.lower) <= d)
          << "k " << k << " far " << far << " tol " << tol << ": lower " << res.lower << " above the exact distance "
          << static_cast<double>(d) << " by " << static_cast<double>(static_cast<Quad>(res.lower) - d);
      EXPECT_TRUE(d <= static_cast<Quad>(res.upper)) << "k " << k << " tol " << tol << ": upper below the exact distance";
      EXPECT_TRUE(res.converged) << res.reason;
      EXPECT_LE(res.upper - res.lower, tol);
      tight += static_cast<double>(d - static_cast<Quad>(res.lower)) <= 64 * 2.2e-16 * far;
    }
  }
  // (Measured: 40 of 400. Without the lower bounds' rounding allowance, the
  // no_rounding mutant, all 400 are, and still none above the gap: another
  // allowance of the same size, about the upper bound's, covers the plane
  // bound's rounding here, so this test does not catch that mutant. The
  // tilted coins below do: without the allowance a face point within
  // rounding of the other coin counts as inside it, a false overlap.)
  std::printf("StackedCoins: %d of 400 brackets' lower bounds within 64 ulps of the coordinates below the exact gap\n", tight);
}

// The same coins, tilted (a random rotation, both alike) and touching to
// within a few ulps of their coordinates: gaps of -4 to +4 ulps of the
// coordinates, 1e2 to 1e6 from the origin. A face point of one coin is then
// inside the other only to rounding, and must not count as a shared point.
// (The no_rounding mutant claims overlaps at gaps of 2e-12 here.)
// The exact gap of the given doubles: the posed coins are R q + t exactly (R
// as given: orthogonal to rounding, 1e-16 of the coins' size, far below the
// coordinates' ulps tested here), so their facing faces lie in
// parallel planes spanned by R's first two columns, and the gap is
// n . (tb - ta - h R e_z) / |n| with n = R e_x x R e_y, in binary128 (the
// products exact, |n| by a Newton step from the double root: far below
// the ulps tested).
TEST(SolidBracketExact, TiltedCoinsWithinRoundingOfTouchingClaimNoFalseOverlap) {
  const double h = kCoinHeight;
  const CaseModel m = coins();
  std::mt19937_64 g(20261129);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  int overlaps = 0, touching = 0;
  for (int k = 0; k < 200; ++k) {
    PosedSolid a = m.instances[0], b = m.instances[1];
    const Eigen::Quaterniond q(N(g), N(g), N(g), N(g));
    const Mat3 R = q.normalized().toRotationMatrix();
    a.R = b.R = R;
    const double far = std::pow(10.0, 2 + 4 * U(g));
    a.t = Vec3(far * (U(g) - 0.5), far * (U(g) - 0.5), far * (U(g) - 0.5));
    const double ulp = std::nextafter(far, HUGE_VAL) - far;
    b.t = a.t + (h + std::round(8 * (U(g) - 0.5)) * ulp) * R.col(2);
    Quad n[3], num = 0, n2 = 0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      n[i] = static_cast<Quad>(R(j, 0)) * R(l, 1) - static_cast<Quad>(R(l, 0)) * R(j, 1);
      num += n[i] * (static_cast<Quad>(b.t[i]) - static_cast<Quad>(a.t[i]) - static_cast<Quad>(h) * R(i, 2));
      n2 += n[i] * n[i];
    }
    Quad len = std::sqrt(static_cast<double>(n2));
    len = (len + n2 / len) / 2;
    const Quad gap = num / len;
    const Quad d = gap > 0 ? gap : Quad(0);
    touching += gap <= 0;
    for (const double tol : {1e-6, 1e-12 * far}) {
      DistanceOptions o;
      o.tol = tol;
      const SolidDistanceResult res = solid_distance(a, b, o);
      EXPECT_TRUE(static_cast<Quad>(res.lower) <= d)
          << "k " << k << " far " << far << " gap " << static_cast<double>(gap) << ": lower " << res.lower;
      EXPECT_TRUE(d <= static_cast<Quad>(res.upper))
          << "k " << k << " far " << far << " gap " << static_cast<double>(gap) << ": upper " << res.upper
          << (res.overlap ? " (claims an overlap)" : "");
      overlaps += res.overlap;
    }
  }
  std::printf("TiltedCoins: %d of 200 pairs touch or overlap exactly; %d of 400 answers claim an overlap\n", touching,
              overlaps);
}

// A tol below what doubles resolve at the coordinates: two solids of `file`
// 1e6 from the origin (coordinates' ulps 1.2e-10, rounding allowances about
// 6e-8), `sep` apart along `axis` where they are `contact` thick together,
// asked for a bracket of 1e-12. The answer still holds the exact distance
// (sep less contact, of the doubles, in binary128), says it did not converge
// and why, and is as narrow as the allowances permit. (Every pair near the
// contact is short of the cut by the rounding alone: the query used to
// refine them until the 25,000 leaf pairs of the work budget ran out, about
// 0.1 s, and left a bracket as wide as the gap: 4.8e-4 for the balls.)
void expect_rounding_limited(const char* file, int axis, double sep, double contact) {
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + file);
  const CaseModel m = build_case_model(c, 1e-5);
  PosedSolid a = m.instances[0], b = m.instances[1];
  a.t = Vec3(1e6, -7e5, 3e5);
  b.t = a.t;
  b.t[axis] += sep;
  const Quad d = static_cast<Quad>(b.t[axis]) - static_cast<Quad>(a.t[axis]) - static_cast<Quad>(contact);
  DistanceOptions o;
  o.tol = 1e-12;
  const SolidDistanceResult res = solid_distance(a, b, o);
  EXPECT_TRUE(static_cast<Quad>(res.lower) <= d && d <= static_cast<Quad>(res.upper)) << file;
  EXPECT_FALSE(res.converged) << file;
  EXPECT_NE(res.reason.find("rounding of coordinates"), std::string::npos) << file << ": " << res.reason;
  EXPECT_LT(res.upper - res.lower, 3e-7) << file;
  EXPECT_LT(res.stats.leaf_pairs, 2000) << file;
}

TEST(SolidBracketExact, FarOffAtTolBelowRoundingSayWhy) {
  // Stacked coins 0.1 thick (faces of exact lines), and balls of radius 0.01.
  expect_rounding_limited("/cases/regressions/rounding_stacked_coins.json", 2, 0.11, 0.1);
  expect_rounding_limited("/cases/regressions/upper_rounded_outward_balls.json", 0, 0.05, 0.02);
}

}  // namespace
}  // namespace revdist
