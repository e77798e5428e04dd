// `revdist stress`: seeded near-degenerate families of circle pairs and solid
// pairs, each case checked against its construction's closed form, an
// independent brute force on the true surfaces (compare/brute_force.h), and on a
// sample the certified exact engine; counts bound violations, NaNs, non-converged
// results and worst errors per family. Shards of one seeded stream merge exactly.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/circle3.h"
#include "core/profile.h"
#include "fast/circle_distance.h"
#include "fast/solid_distance.h"

namespace revdist {

// The fast queries under test, injectable so the harness can be shown to catch
// a wrong engine (tests/compare/stress_test.cpp) without touching fast/.
struct StressEngines {
  std::function<SolidDistanceResult(const PosedSolid&, const PosedSolid&, const DistanceOptions&)> solid =
      [](const PosedSolid& a, const PosedSolid& b, const DistanceOptions& o) { return solid_distance(a, b, o); };
  std::function<Circle3Circle3Result(const Circle3&, const Circle3&)> circle =
      [](const Circle3& a, const Circle3& b) { return circle3_circle3_distance(a, b); };
};

struct StressOptions {
  // Fit bound and tolerance of the fast query, relative to the size of the
  // case (the larger profile extent), so scaled families ask the same digits.
  double eps = 1e-5;
  double tol = 1e-6;
  // Solid cases with index % exact_every == 0 also run exact/ (0: never), to a
  // width of tol with a work budget (exact/ takes 0.1-70 s per such query today;
  // over budget it still proves a wider interval, or says it could not certify).
  int exact_every = 100;
  long exact_max_boxes = 5000;
  int circle_exact_every = 1;  // circle cases checked by the certified circle distance
};

// One generated case: a two-instance revdist/1 case (one query) or a circle pair.
struct StressCase {
  std::string family;
  long index = 0;
  bool is_circle = false;
  Case solids;            // instances 0 and 1, query (0, 1)
  Circle3 a, b;           // circle families
  double expected = 0.0;  // distance of the construction (NaN when it has none)
  std::string note;       // what was built (parameters), for the worst-case record
};

struct FamilyInfo {
  std::string name;
  bool circle = false;
  std::string description;
};
const std::vector<FamilyInfo>& stress_families();

// Case `index` of a family from the run's seed; each index has its own stream.
StressCase make_stress_case(const std::string& family, long index, std::uint64_t seed);

// The case as a committed file: revdist/1 (solids) or revdist-circles/1, full precision.
nlohmann::json stress_case_json(const StressCase& c);

struct FamilyStats {
  std::string name;
  bool circle = false;
  long n = 0;
  long violations = 0;
  long nans = 0;
  long not_converged = 0;
  double max_abs_error = 0.0;  // |distance - reference| (reference: closed form, else exact, else brute)
  double max_rel_error = 0.0;  // the same over max(reference, tol)
  long exact_checked = 0;      // certified by exact/ and compared
  long exact_uncertified = 0;  // exact/ ran but could not certify (budget or reason)
  long brute_checked = 0;
  long expected_checked = 0;
  // Violations by kind: lower_above_reference, upper_below_reference,
  // lower_above_brute, exact_disjoint, width_over_tol, witness_off, inconsistent.
  std::map<std::string, long> kinds;
  double time_s = 0.0;  // thread CPU seconds of the family (all checks included)
  // The worst case: a violation (largest margin) before any error; ties to the lower index.
  bool worst_violation = false;
  double worst_score = -1.0;
  long worst_index = -1;
  std::string worst_what;
  nlohmann::json worst_case;
  // The cases that did not converge, by index (the lowest kListedUnconverged
  // of them): what the query said and the case file, to rerun one alone.
  struct Unconverged {
    long index = 0;
    std::string what;
    nlohmann::json case_json;
  };
  std::vector<Unconverged> unconverged;
};
constexpr std::size_t kListedUnconverged = 10;

struct StressReport {
  std::uint64_t seed = 0;
  long n = 0;  // cases per family in the whole stream
  int shard_k = 1, shard_m = 1;  // shard K of M (1-based); merged reports say 1/1
  StressOptions options;
  std::vector<FamilyStats> families;
};

// Runs the named families (cases index % M == K - 1 of n). progress(done, total) may be empty.
StressReport run_stress(const std::vector<std::string>& families, long n, std::uint64_t seed, int shard_k, int shard_m,
                        const StressOptions& options, const StressEngines& engines = {},
                        const std::function<void(long, long)>& progress = {});

nlohmann::json stress_json(const StressReport& r);
StressReport stress_from_json(const nlohmann::json& j);  // throws std::runtime_error on a malformed record
// Combines shards of one run: same seed, n, options and families, disjoint
// shards covering 1..M. Counts add, maxima and worst cases combine exactly.
StressReport merge_stress(const std::vector<StressReport>& shards);

}  // namespace revdist
