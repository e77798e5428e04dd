// The stress harness (compare/stress.h, compare/brute_force.h): a small run of
// every family is clean; a deliberately wrong engine (an eps dropped from the
// lower bound) is caught in every family; shards merge to exactly the
// unsharded run; worst cases are valid case files; the references themselves
// (brute force, support function) match closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "compare/brute_force.h"
#include "compare/stress.h"
#include "core/case_io.h"
#include "core/circle_io.h"

namespace revdist {
namespace {

std::uint64_t seed(std::uint64_t fallback, const char* what) {
  const char* s = std::getenv("REVDIST_SEED");
  const std::uint64_t v = s ? std::strtoull(s, nullptr, 10) : fallback;
  std::printf("[ seed     ] %s: REVDIST_SEED=%llu\n", what, static_cast<unsigned long long>(v));
  return v;
}

std::vector<std::string> all_families() {
  std::vector<std::string> v;
  for (const FamilyInfo& f : stress_families()) v.push_back(f.name);
  return v;
}

StressOptions quick_options() {
  StressOptions o;
  o.exact_every = 40;        // index 0 of each solid family: 16 certified checks
  o.exact_max_boxes = 2000;  // keeps each under ~0.5 s; over budget it still proves a wider interval
  o.circle_exact_every = 4;
  return o;
}

TEST(Stress, EveryFamilyCleanOnASmallRun) {
  const std::uint64_t s = seed(1, "Stress.EveryFamilyCleanOnASmallRun");
  const StressReport r = run_stress(all_families(), 40, s, 1, 1, quick_options());
  ASSERT_EQ(r.families.size(), stress_families().size());
  for (const FamilyStats& f : r.families) {
    std::printf("%-24s n=%ld violations=%ld nans=%ld not_converged=%ld max_abs=%.3g max_rel=%.3g exact=%ld/%ld "
                "time=%.2fs\n",
                f.name.c_str(), f.n, f.violations, f.nans, f.not_converged, f.max_abs_error, f.max_rel_error,
                f.exact_checked, f.exact_checked + f.exact_uncertified, f.time_s);
    EXPECT_EQ(f.n, 40) << f.name;
    EXPECT_EQ(f.violations, 0) << f.name << ": " << f.worst_what << "\n" << f.worst_case.dump();
    EXPECT_EQ(f.nans, 0) << f.name;
    EXPECT_EQ(f.not_converged, 0) << f.name << ": " << f.worst_what;
    EXPECT_EQ(f.brute_checked, f.n) << f.name;
    EXPECT_GE(f.exact_checked, 1) << f.name;
    if (!f.circle) {
      // Every solid family has a closed form for every case (mirror and tube pairs, containment).
      EXPECT_EQ(f.expected_checked, f.n) << f.name;
      // The bracket is at most tol wide, so the middle is within tol / 2 of it (tol relative to size 1..1e6).
      EXPECT_LE(f.max_rel_error, 0.5 + 1e-6) << f.name;
    }
  }
}

double extent(const Profile& p) {
  double s = 0;
  for (const Piece& piece : p.pieces)
    for (const Vec2& q : piece.points) s = std::max({s, std::abs(q.x()), std::abs(q.y())});
  return s;
}

// The mutant of issue 7: one fit eps (1e-5 of the case's size, as the harness
// asks) dropped from the lower bound, the bracket kept consistent. Not the trees'
// claimed error: straight pieces fit exactly, so that can be 0.
TEST(Stress, DroppedEpsInTheLowerBoundIsCaughtInEveryFamily) {
  const std::uint64_t s = seed(2, "Stress.DroppedEpsInTheLowerBoundIsCaughtInEveryFamily");
  StressEngines mutant;
  mutant.solid = [](const PosedSolid& a, const PosedSolid& b, const DistanceOptions& o) {
    SolidDistanceResult r = solid_distance(a, b, o);
    r.lower += StressOptions{}.eps * std::max(extent(*a.profile), extent(*b.profile));
    r.upper = std::max(r.upper, r.lower);
    r.distance = 0.5 * (r.lower + r.upper);
    return r;
  };
  // The circle kernel's analogue: an error of 1e-9 x the coordinates' scale, far
  // outside its 64-ulp bracket (centres 1e6 from the origin round at ~1e-10).
  mutant.circle = [](const Circle3& a, const Circle3& b) {
    Circle3Circle3Result r = circle3_circle3_distance(a, b);
    r.distance += 1e-9 * std::max({a.radius, b.radius, (a.center - b.center).norm(), a.center.cwiseAbs().maxCoeff(),
                                   b.center.cwiseAbs().maxCoeff()});
    return r;
  };
  StressOptions o = quick_options();
  o.exact_every = 0;  // the closed forms and the brute force must catch it on their own
  const StressReport r = run_stress(all_families(), 6, s, 1, 1, o, mutant);
  for (const FamilyStats& f : r.families) {
    std::printf("%-24s violations %ld/%ld\n", f.name.c_str(), f.violations, f.n);
    EXPECT_EQ(f.violations, f.n) << f.name << " let a wrong engine through: " << f.worst_what;
    EXPECT_TRUE(f.worst_violation) << f.name;
  }
}

nlohmann::json without_times(nlohmann::json j) {
  j.erase("run");
  j["totals"].erase("time_s");
  for (auto& f : j["families"]) f.erase("time_s");
  return j;
}

TEST(Stress, MergedShardsEqualTheUnshardedRun) {
  const std::uint64_t s = seed(3, "Stress.MergedShardsEqualTheUnshardedRun");
  const std::vector<std::string> fams = {"circle_villarceau", "circle_tilt_ladder", "tangent_touching",
                                         "interlocked_rings", "near_parallel_planes"};
  StressOptions o = quick_options();
  o.exact_every = 5;
  o.exact_max_boxes = 500;
  const StressReport whole = run_stress(fams, 11, s, 1, 1, o);
  std::vector<StressReport> shards;
  for (int k : {3, 1, 2}) {
    // Through JSON text, as shards travel between machines.
    const std::string text = stress_json(run_stress(fams, 11, s, k, 3, o)).dump();
    shards.push_back(stress_from_json(nlohmann::json::parse(text)));
  }
  const StressReport merged = merge_stress(shards);
  EXPECT_EQ(without_times(stress_json(merged)), without_times(stress_json(whole)));
  long n = 0;
  for (const FamilyStats& f : merged.families) n += f.n;
  EXPECT_EQ(n, 55);
  // Not a complete set, or a shard twice: refused.
  EXPECT_THROW(merge_stress({shards[0], shards[1]}), std::runtime_error);
  EXPECT_THROW(merge_stress({shards[0], shards[0], shards[1]}), std::runtime_error);
}

// A query that does not converge is listed by index (the lowest ones), with
// the query's reason and its case file, and the lists of shards merge to the
// unsharded run's. The engine here fails to converge on every third case.
TEST(Stress, UnconvergedCasesAreListedAndMerge) {
  const std::uint64_t s = seed(5, "Stress.UnconvergedCasesAreListedAndMerge");
  StressEngines stalling;
  long calls = 0;
  stalling.solid = [&calls](const PosedSolid& a, const PosedSolid& b, const DistanceOptions& o) {
    SolidDistanceResult r = solid_distance(a, b, o);
    if (calls++ % 3 == 0) {
      r.converged = false;
      r.reason = "test: stalled on purpose";
    }
    return r;
  };
  StressOptions o = quick_options();
  o.exact_every = 0;
  const std::vector<std::string> fams = {"tangent_touching"};
  // Unsharded, every case in index order: cases 0, 3, ..., 33 stall (12 of 36).
  const StressReport whole = run_stress(fams, 36, s, 1, 1, o, stalling);
  const FamilyStats& f = whole.families.at(0);
  EXPECT_EQ(f.not_converged, 12);
  ASSERT_EQ(f.unconverged.size(), kListedUnconverged);
  for (std::size_t i = 0; i < f.unconverged.size(); ++i) {
    EXPECT_EQ(f.unconverged[i].index, static_cast<long>(3 * i));
    EXPECT_NE(f.unconverged[i].what.find("test: stalled on purpose"), std::string::npos) << f.unconverged[i].what;
    EXPECT_EQ(f.unconverged[i].case_json, stress_case_json(make_stress_case("tangent_touching", 3 * i, s)));
  }
  // Three shards (each stalls on its own every third case), through JSON text.
  std::vector<StressReport> shards;
  std::vector<long> expected;
  for (int k : {1, 2, 3}) {
    calls = 0;
    const std::string text = stress_json(run_stress(fams, 36, s, k, 3, o, stalling)).dump();
    shards.push_back(stress_from_json(nlohmann::json::parse(text)));
    for (long i = k - 1, j = 0; i < 36; i += 3, ++j)
      if (j % 3 == 0) expected.push_back(i);
  }
  std::sort(expected.begin(), expected.end());
  expected.resize(kListedUnconverged);
  const StressReport merged = merge_stress(shards);
  const FamilyStats& m = merged.families.at(0);
  EXPECT_EQ(m.not_converged, 12);
  ASSERT_EQ(m.unconverged.size(), kListedUnconverged);
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(m.unconverged[i].index, expected[i]);
  // A list longer than the count is refused.
  nlohmann::json bad = stress_json(whole);
  bad["families"][0]["not_converged"] = 2;
  EXPECT_THROW(stress_from_json(bad), std::runtime_error);
}

TEST(Stress, WorstCasesAreValidCaseFiles) {
  const std::uint64_t s = seed(4, "Stress.WorstCasesAreValidCaseFiles");
  for (const FamilyInfo& f : stress_families()) {
    const StressCase c = make_stress_case(f.name, 7, s);
    const std::string path = testing::TempDir() + "revdist_stress_case_" + f.name + ".json";
    std::ofstream(path) << stress_case_json(c).dump(1);
    if (f.circle) {
      const std::vector<CirclePair> pairs = read_circle_pairs(path);
      ASSERT_EQ(pairs.size(), 1u) << f.name;
      EXPECT_EQ(pairs[0].a.center, c.a.center) << f.name;  // full precision round trip
      EXPECT_EQ(pairs[0].b.radius, c.b.radius) << f.name;
    } else {
      // read_case validates every profile (joins, ends, r >= 0, self-intersection).
      const Case back = read_case(path);
      ASSERT_EQ(back.instances.size(), 2u) << f.name;
      ASSERT_EQ(back.queries.size(), 1u) << f.name;
      EXPECT_EQ(back.instances[1].pose.q, c.solids.instances[1].pose.q) << f.name;
      EXPECT_EQ(back.instances[1].pose.translation, c.solids.instances[1].pose.translation) << f.name;
    }
    std::remove(path.c_str());
  }
}

Profile ball(double s) {
  Piece arc;
  arc.kind = PieceKind::arc;
  arc.degree = 2;
  arc.points = {Vec2(0, -s), Vec2(s, 0), Vec2(0, s)};
  Profile p;
  p.pieces = {arc};
  return p;
}

TEST(BruteForce, TwoBallsAndSupportFunctionMatchClosedForms) {
  const Profile a = ball(1.0), b = ball(0.5);
  const ProfileNearest na(a), nb(b);
  const Eigen::Quaterniond q(Eigen::Vector4d(0.2, 0.7, -0.1, 0.4).normalized());
  const PosedProfile pa{&na, Mat3::Identity(), Vec3(0.1, 0.2, 0.3)};
  const PosedProfile pb{&nb, q.toRotationMatrix(), Vec3(0.1, 0.2, 0.3) + 1.7 * Vec3(0, 0.6, 0.8)};
  const BruteResult r = brute_surface_distance(pa, pb);
  // Newton converges to the rounding of the distance evaluation: a few ulps of the coordinates.
  EXPECT_NEAR(r.distance, 0.2, 1e-12);
  EXPECT_GE(r.distance, 0.2 - 1e-15);
  EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-15);
  EXPECT_NEAR(pa.surface_distance(r.point_a), 0.0, 1e-15);
  EXPECT_NEAR(pb.surface_distance(r.point_b), 0.0, 1e-15);
  // Support of a ball is its radius in every direction; of a can of radius r, height h: r s + h max(c, 0).
  EXPECT_NEAR(profile_support(a, Vec3(0.6, 0, 0.8)), 1.0, 1e-15);
  Profile can;
  for (auto [p, q2] : {std::pair{Vec2(0, 0), Vec2(0.5, 0)}, {Vec2(0.5, 0), Vec2(0.5, 2)}, {Vec2(0.5, 2), Vec2(0, 2)}}) {
    Piece l;
    l.points = {p, q2};
    can.pieces.push_back(l);
  }
  EXPECT_NEAR(profile_support(can, Vec3(0.6, 0, 0.8)), 0.5 * 0.6 + 2 * 0.8, 1e-15);
  EXPECT_NEAR(profile_support(can, Vec3(0.6, 0, -0.8)), 0.5 * 0.6, 1e-15);
}

}  // namespace
}  // namespace revdist
