// Random stress of the fast solid distance (fast/solid_distance, paper section
// 4.2) on the paper's five models: random rotations, b placed at a random
// target separation (log-uniform from 1e-6 to 1 x size, and some overlaps)
// along a random direction. Every result is checked against the brute force on
// the true surfaces (lower never above it) and its certificates; violations
// and non-converged results are counted and printed as ready-to-commit
// revdist/1 cases. Label "stress": REVDIST_STRESS_N trials (default 300),
// REVDIST_SEED.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"
#include "solid_test_util.h"

namespace revdist {
namespace {

using namespace solid_test;

constexpr double kEps = 1e-5;
constexpr double kTol = 1e-6;

int trials() {
  const char* s = std::getenv("REVDIST_STRESS_N");
  return s ? std::atoi(s) : 300;
}

std::string instance_json(const char* name, const std::string& solid, const std::array<double, 4>& q, const Vec3& t) {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "{\"name\": \"%s\", \"solid\": \"%s\", \"rotation\": [%.17g, %.17g, %.17g, %.17g], "
                "\"translation\": [%.17g, %.17g, %.17g]}",
                name, solid.c_str(), q[0], q[1], q[2], q[3], t.x(), t.y(), t.z());
  return buf;
}

TEST(SolidDistanceStress, RandomPosesOfPaperModels) {
  const std::uint64_t seed = test_seed(9001, "SolidDistanceStress");
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  const Case c = read_case(source_path("cases/models/paper_pairs.json"));
  const CaseModel m = build_case_model(c, kEps);
  std::vector<std::unique_ptr<ProfileSampler>> samplers;
  for (const PosedSolid& s : m.instances) samplers.push_back(std::make_unique<ProfileSampler>(*s.profile, 4000));

  const int n = trials();
  int violations = 0, cert_failures = 0, not_converged = 0, overlaps = 0, near = 0;
  double worst_excess = 0.0, worst_gap = 0.0;
  long node_pairs = 0;
  for (int k = 0; k < n; ++k) {
    const std::size_t ia = g() % m.instances.size(), ib = g() % m.instances.size();
    const std::array<double, 4> qa = random_quaternion(g), qb = random_quaternion(g);
    PosedSolid A = m.instances[ia], B = m.instances[ib];
    A.R = rotation_of(qa);
    B.R = rotation_of(qb);
    A.t = Vec3(N(g), N(g), N(g));
    const Vec3 dir = Vec3(N(g), N(g), N(g)).normalized();
    // Target separation: 10% overlapping, else log-uniform in [1e-6, 1] (sizes are ~1.5).
    const double target = U(g) < 0.1 ? -0.05 : std::pow(10.0, -6.0 + 6.0 * U(g));
    B.t = A.t + 2.0 * dir;
    for (int it = 0; it < 4 && target > 0; ++it) {
      const SolidDistanceResult r0 = solid_distance(A, B, DistanceOptions{1e-9});
      if (r0.overlap || !std::isfinite(r0.distance)) {
        B.t += 0.5 * dir;
        continue;
      }
      B.t += (target - r0.distance) * dir;
    }
    if (target < 0) B.t = A.t + 0.4 * dir;
    const SolidDistanceResult r = solid_distance(A, B, DistanceOptions{kTol});
    node_pairs += r.stats.node_pairs;
    overlaps += r.overlap;
    near += !r.overlap && r.upper < 1e-3;
    const int failures_before = ::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count();
    const double scale = query_scale(A, B);
    expect_certificates(A, B, r, *samplers[ia], *samplers[ib], 1e-9 * scale, "trial " + std::to_string(k));
    const bool cert_bad = ::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count() != failures_before;
    const BruteResult b = brute_surface_distance(A, B);
    const double excess = r.lower - b.distance;
    worst_excess = std::max(worst_excess, excess);
    if (r.converged) worst_gap = std::max(worst_gap, r.upper - r.lower);
    const bool violated = excess > 1e-12 * scale || (r.converged && r.upper - r.lower > kTol + 1e-12 * scale);
    if (!r.converged) ++not_converged;
    if (violated || cert_bad) {
      violations += violated;
      cert_failures += cert_bad;
      std::printf("[ VIOLATION] trial %d %s-%s: %s brute=%.17g (lower - brute = %.3g)\n  case: {\"format\": \"revdist/1\", "
                  "\"instances\": [%s, %s]}\n",
                  k, c.instances[ia].name.c_str(), c.instances[ib].name.c_str(), describe(r).c_str(), b.distance,
                  excess, instance_json("a", c.solids[c.instances[ia].solid].name, qa, A.t).c_str(),
                  instance_json("b", c.solids[c.instances[ib].solid].name, qb, B.t).c_str());
    } else if (!r.converged) {
      std::printf("[ not conv ] trial %d %s-%s: %s\n", k, c.instances[ia].name.c_str(), c.instances[ib].name.c_str(),
                  describe(r).c_str());
    }
  }
  std::printf("[ stats    ] %d trials: %d lower-bound/tol violations (worst lower - brute %.3g), %d certificate "
              "failures, %d not converged, %d overlaps, %d within 1e-3, worst converged gap %.3g, mean node pairs %.1f\n",
              n, violations, worst_excess, cert_failures, not_converged, overlaps, near, worst_gap,
              n ? double(node_pairs) / n : 0.0);
  EXPECT_EQ(violations, 0);
}

}  // namespace
}  // namespace revdist
