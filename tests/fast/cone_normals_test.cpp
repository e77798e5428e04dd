// Tests of the cone normal lines (fast/cone_normals.h): every pair returned is
// a common normal of the two cones, and no candidate is dropped silently (the
// output capacities of the header hold, overflows count as fallbacks).
#include "fast/cone_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "fast/patch.h"
#include "tests/fast/biarc_test_util.h"

namespace revdist {
namespace {

using testing_util::test_seed;

Arc2 segment(double r, double z, double tr, double tz, double length) {
  Arc2 a;
  a.start = Vec2(r, z);
  a.tangent = Vec2(tr, tz).normalized();
  a.curvature = 0.0;
  a.length = length;
  return a;
}

// A frame whose third column is the unit axis `ax`.
Mat3 frame_with_axis(const Vec3& ax) {
  Vec3 e1 = Vec3::UnitZ().cross(ax);
  if (e1.norm() < 1e-12) return Mat3::Identity();
  e1.normalize();
  Mat3 R;
  R.col(0) = e1;
  R.col(1) = ax.cross(e1);
  R.col(2) = ax;
  return R;
}

// World unit normal of straight patch P at world point x (on its cone).
Vec3 cone_normal(const Patch& P, const Vec3& x) {
  Vec3 e_r;
  patch_local(P, x, &e_r);
  return (P.n.x() * e_r + P.n.y() * P.a).normalized();
}

// Every foot lies on its cone and every line is normal to the cone(s) it meets.
// Feet are solved on the cone line exactly: 1e-9 (scaled units ~1) is far
// above their rounding and far below a wrong candidate.
void check_pairs(const Patch& A, const Patch& B, int n, const Vec3* xs, const Vec3* ys) {
  for (int i = 0; i < n; ++i) {
    const bool has_x = xs[i].allFinite(), has_y = ys[i].allFinite();
    ASSERT_TRUE(has_x || has_y) << i;
    if (has_x) {
      EXPECT_NEAR(patch_surface_function(A, patch_local(A, xs[i])), 0.0, 1e-9) << i;
    }
    if (has_y) {
      EXPECT_NEAR(patch_surface_function(B, patch_local(B, ys[i])), 0.0, 1e-9) << i;
    }
    if (has_x && has_y && (xs[i] - ys[i]).norm() > 1e-6) {
      const Vec3 d = (ys[i] - xs[i]).normalized();
      // The kernel accepts a foot where cos(line, normal) >= 1 - 1e-6, i.e.
      // within ~1.4e-3 rad; lines through a point where the axes meet are not
      // polished further (up to ~9e-4 rad seen).
      EXPECT_LE(d.cross(cone_normal(A, xs[i])).norm(), 1.5e-3) << i;
      EXPECT_LE(d.cross(cone_normal(B, ys[i])).norm(), 1.5e-3) << i;
    }
  }
}

// B's axis crosses A's axis: the squared system's root at the crossing is
// of high multiplicity and reported several times, each giving the lines
// through the crossing. 24 pairs here (8 distinct, three times): the old fixed
// capacity of 16 cut the list, and a distinct pair coming after such repeats
// would have been lost without a trace.
TEST(ConeNormals, MeetingAxesKeepEveryCandidate) {
  const Patch A = make_patch(segment(0.36307288761763934, -0.95719143986726896, 0.54478259390571115,
                                     -0.83857732224128567, 1.4044911933308757),
                             Mat3::Identity(), Vec3::Zero());
  const Patch B = make_patch(segment(0.20297009098923638, -0.55746835213636592, -0.00063030387857148284,
                                     0.99999980135849065, 0.7005829197522957),
                             frame_with_axis(Vec3(-0.69301185666659393, -0.61407714747553876, 0.37768217255759601)),
                             Vec3(0, 0, 0.65914588087168791));
  ASSERT_TRUE(A.straight && B.straight);
  const std::uint64_t before = cone_normals_fallbacks();
  Vec3 xs[kConeConeNormalsMax], ys[kConeConeNormalsMax];
  bool deg = true;
  const int n = cone_cone_normals(A, B, xs, ys, &deg);
  EXPECT_EQ(n, 24);
  EXPECT_FALSE(deg);
  EXPECT_EQ(cone_normals_fallbacks(), before);
  std::vector<Vec3> distinct;
  for (int i = 0; i < n; ++i) {
    bool seen = false;
    for (const Vec3& y : distinct) seen |= (y - ys[i]).norm() < 1e-9;
    if (!seen) distinct.push_back(ys[i]);
  }
  EXPECT_EQ(distinct.size(), 8u);
  check_pairs(A, B, n, xs, ys);
}

// Random cone pairs in general position, with meeting axes and with nearly
// parallel axes (the resultant vanishes: Newton from a grid of starts).
TEST(ConeNormals, RandomPairsAreCommonNormalsWithinCapacity) {
  const std::uint64_t seed = test_seed(11);
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const std::uint64_t before = cone_normals_fallbacks();
  int most = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    SCOPED_TRACE(trial);
    auto seg = [&] {
      const double ang = M_PI * U(g);
      return segment(0.1 + std::abs(U(g)), U(g), std::cos(ang), std::sin(ang), 0.5 + std::abs(U(g)));
    };
    const Arc2 sa = seg(), sb = seg();
    const int mode = trial % 3;
    Vec3 ax = mode == 1 ? Vec3(1e-9 * U(g), 1e-9 * U(g), 1) : Vec3(U(g), U(g), U(g));
    ax.normalize();
    Vec3 t = Vec3::Zero();
    if (mode == 1) t = 0.5 * Vec3(U(g), U(g), U(g));
    if (mode == 2) t = Vec3(0, 0, U(g));
    const Patch A = make_patch(sa, Mat3::Identity(), Vec3::Zero());
    const Patch B = make_patch(sb, frame_with_axis(ax), t);
    if (!A.straight || !B.straight) continue;
    Vec3 xs[kConeConeNormalsMax], ys[kConeConeNormalsMax];
    bool deg = false;
    const int n = cone_cone_normals(A, B, xs, ys, &deg);
    ASSERT_LE(n, kConeConeNormalsMax);
    most = std::max(most, n);
    check_pairs(A, B, n, xs, ys);
  }
  std::printf("most pairs from one call: %d (capacity %d)\n", most, kConeConeNormalsMax);
  EXPECT_EQ(cone_normals_fallbacks(), before);
}

}  // namespace
}  // namespace revdist
