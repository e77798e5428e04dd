// The exact engine as the oracle of the fast one on the circle layer: every
// family of compare/circle_families, >= 10^4 random pairs, and the closed forms.
// Targets (issue 2): |fast - exact| <= 1e-13 * scale on random pairs and
// <= 1e-10 * scale on every degenerate family, scale = max(radii, centre distance).
// Binormal-line counts of both engines on the bundled cases/circles files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <ostream>
#include <string>

#include "compare/circle_families.h"
#include "core/circle_io.h"
#include "exact/circle_distance_exact.h"
#include "fast/circle_distance.h"

namespace revdist {
namespace {

std::uint64_t test_seed() {
  const char* s = std::getenv("REVDIST_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 20261121u;
}

// Distance from v to the interval [lo, hi] (0 inside).
double outside(double v, double lo, double hi) { return v < lo ? lo - v : v > hi ? v - hi : 0.0; }

struct FamilyCase {
  std::string family;
  int n;
};
void PrintTo(const FamilyCase& c, std::ostream* os) { *os << c.family << " x" << c.n; }

class CircleFastVsExact : public testing::TestWithParam<FamilyCase> {};

TEST_P(CircleFastVsExact, FastWithinTargetOfCertifiedInterval) {
  const FamilyCase& fc = GetParam();
  const std::uint64_t seed = test_seed();
  std::printf("family %s, n = %d, REVDIST_SEED=%llu\n", fc.family.c_str(), fc.n,
              static_cast<unsigned long long>(seed));
  const auto& families = circle_families();
  const auto it = std::find_if(families.begin(), families.end(),
                               [&](const CircleFamily& f) { return f.name == fc.family; });
  ASSERT_NE(it, families.end());
  const double target = it->degenerate ? 1e-10 : 1e-13;

  double worst = 0.0, worst_closed = 0.0;
  int not_certified = 0;
  for (const auto& p : make_circle_family(fc.family, fc.n, seed)) {
    const auto f = circle3_circle3_distance(p.pair.a, p.pair.b);
    const auto e = circle3_circle3_distance_exact(p.pair.a, p.pair.b);
    if (e.status == ExactStatus::not_certified) {
      ++not_certified;
      ADD_FAILURE() << "not certified: " << e.reason;
      continue;
    }
    ASSERT_LE(e.lower, e.upper);
    ASSERT_GE(e.lower, 0.0);
    const double err = outside(f.distance, e.lower, e.upper) / p.scale;
    worst = std::max(worst, err);
    EXPECT_LE(err, target) << "fast " << f.distance << " vs exact [" << e.lower << ", " << e.upper
                           << "], scale " << p.scale;
    // `revdist circles` reports the fast bracket as distance +- 64 ulps of the
    // scale (cli/cmd_circles.cpp): that bracket must meet the certified one.
    EXPECT_LE(err, 64 * std::numeric_limits<double>::epsilon()) << "fast bracket misses the certified interval";
    // The fast closest pair must realise its distance. The points are world
    // coordinates: each carries rounding of a few ulps of its magnitude (1e6
    // from the origin: ~1e-10), on top of 1e-12 of the pair's scale.
    const double coord = std::max(f.point_a.cwiseAbs().maxCoeff(), f.point_b.cwiseAbs().maxCoeff());
    EXPECT_NEAR((f.point_a - f.point_b).norm(), f.distance,
                1e-12 * p.scale + 16 * std::numeric_limits<double>::epsilon() * coord);
    if (!std::isnan(p.expected)) {
      // The closed form holds before the rigid motion is rounded to double; the
      // rounding moves the circles by a few ulps of the scale (1e-14 allows 45 ulps).
      const double closed = outside(p.expected, e.lower, e.upper) / p.scale;
      worst_closed = std::max(worst_closed, closed);
      EXPECT_LE(closed, 1e-14) << "closed form " << p.expected << " vs exact [" << e.lower << ", "
                               << e.upper << "]";
    }
  }
  std::printf("family %s: worst |fast - exact| / scale = %.3g, worst closed-form miss / scale = %.3g, "
              "not certified = %d\n",
              fc.family.c_str(), worst, worst_closed, not_certified);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

std::vector<FamilyCase> all_cases() {
  std::vector<FamilyCase> v;
  for (const auto& f : circle_families()) v.push_back({f.name, f.name == "random" ? 10000 : 300});
  return v;
}

INSTANTIATE_TEST_SUITE_P(Families, CircleFastVsExact, testing::ValuesIn(all_cases()),
                         [](const testing::TestParamInfo<FamilyCase>& info) { return info.param.family; });

// Is the pair within rounding of a continuum of binormal lines? Judged apart
// from both engines, in long double: a point circle within 1e-12 of the
// scale from the other's axis (a cone of lines), or a branch derivative
// ψσ = Δ·T - σR_a(ρ·ρ') / ρ flat (|ψσ| <= 1e-12·scale², ~4500 ulps of
// a ψ of size scale², far below a generic pair's) along an eighth of b or more.
bool continuum_to_rounding(const Circle3& a, const Circle3& b) {
  using LD = long double;
  const LD scale = std::max({a.radius, b.radius, (a.center - b.center).norm()});
  auto unit = [](const Vec3& n) {
    const Eigen::Matrix<LD, 3, 1> v = n.cast<LD>();
    return Eigen::Matrix<LD, 3, 1>(v / v.norm());
  };
  if (a.radius == 0 || b.radius == 0) {
    const Circle3& c = a.radius == 0 ? b : a;
    const Circle3& q = a.radius == 0 ? a : b;
    const Eigen::Matrix<LD, 3, 1> n = unit(c.normal), d = (q.center - c.center).cast<LD>();
    return (d - d.dot(n) * n).norm() <= 1e-12L * scale;
  }
  const Eigen::Matrix<LD, 3, 1> na = unit(a.normal), nb = unit(b.normal), ca = a.center.cast<LD>(),
                                cb = b.center.cast<LD>();
  const Eigen::Matrix<LD, 3, 1> e = std::abs(nb[0]) < 0.6L ? Eigen::Matrix<LD, 3, 1>(1, 0, 0)
                                                            : Eigen::Matrix<LD, 3, 1>(0, 1, 0);
  const Eigen::Matrix<LD, 3, 1> u = nb.cross(e).normalized(), v = nb.cross(u);
  constexpr int kSamples = 256;
  for (int sg : {1, -1}) {
    int run = 0, best = 0;
    for (int i = 0; i < 2 * kSamples; ++i) {  // twice round: runs across the seam
      const LD th = 2 * 3.14159265358979323846L * (i % kSamples) / kSamples;
      const Eigen::Matrix<LD, 3, 1> d = cb - ca + LD(b.radius) * (std::cos(th) * u + std::sin(th) * v);
      const Eigen::Matrix<LD, 3, 1> t = LD(b.radius) * (std::cos(th) * v - std::sin(th) * u);
      const Eigen::Matrix<LD, 3, 1> dp = d - d.dot(na) * na, tp = t - t.dot(na) * na;
      const LD rho = dp.norm();
      const LD psi = rho > 0 ? d.dot(t) - sg * LD(a.radius) * dp.dot(tp) / rho : 0;
      run = std::abs(psi) <= 1e-12L * scale * scale ? run + 1 : 0;
      best = std::max(best, std::min(run, kSamples));
    }
    if (best >= kSamples / 8) return true;
  }
  return false;
}

// Both engines count binormal lines one way (README, `circles`): equal counts
// on every bundled pair, except where fast reports a continuum (-1) that the
// given doubles miss by rounding; exact then counts the lines of the doubles,
// and the test checks on its own that the pair is a continuum to rounding.
TEST(CircleBinormalCounts, FastAndExactAgreeOnBundledCases) {
  int pairs = 0, equal = 0, continuum = 0, flat_finite = 0;
  const std::string dir = std::string(REVDIST_SOURCE_DIR) + "/cases/circles";
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  for (const std::string& file : files) {
    const auto list = read_circle_pairs(file);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const CirclePair& p = list[i];
      bool inf = false;
      const int fast = static_cast<int>(circle3_circle3_binormals(p.a, p.b, &inf).size());
      const int fast_count = inf ? -1 : fast;
      const auto e = circle3_circle3_distance_exact(p.a, p.b);
      ASSERT_NE(e.status, ExactStatus::not_certified) << file << " #" << i << ": " << e.reason;
      ++pairs;
      if (fast_count == e.binormals) {
        ++equal;
        // The flatness judge must not call every pair a continuum.
        if (file.find("/random.json") != std::string::npos) {
          EXPECT_FALSE(continuum_to_rounding(p.a, p.b)) << i;
        }
        flat_finite += fast_count >= 0 && continuum_to_rounding(p.a, p.b);
        continue;
      }
      EXPECT_EQ(fast_count, -1) << file << " #" << i << ": fast " << fast_count << " lines, exact " << e.binormals;
      EXPECT_GE(e.binormals, 0) << file << " #" << i;
      EXPECT_TRUE(continuum_to_rounding(p.a, p.b)) << file << " #" << i << ": fast says a continuum, exact "
                                                   << e.binormals << " lines, and the pair is not flat";
      ++continuum;
    }
  }
  std::printf("binormal counts: %d pairs, %d equal (%d of them flat along an arc), %d continua to rounding "
              "(fast -1, exact finite)\n", pairs, equal, flat_finite, continuum);
  EXPECT_GE(pairs, 200);
}

}  // namespace
}  // namespace revdist
