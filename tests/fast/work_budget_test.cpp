// The fast query's work budget (fast/solid_distance.h: max_node_pairs,
// max_patch_pairs): a query that cannot converge ends within it, says which
// budget ran out, and still returns a finite bracket that holds the distance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist {
namespace {

std::string source(const std::string& rel) { return std::string(REVDIST_SOURCE_DIR) + "/" + rel; }

// A rod in a cup, nested near-parallel cones (see the file's comment): it ran
// for minutes; now it converges within the kernel budget (9 kernels at eps
// 1e-5 since the local proof hands back the nearest box centre it saw; about
// 270 before), and a kernel budget below what it needs ends it at once,
// naming itself, with a bracket that still holds exact/'s certified interval
// [0.099984462, 0.099984933].
TEST(WorkBudget, NestedNearParallelConesEndWithinTheKernelBudget) {
  const Case c = read_case(source("cases/regressions/budget_nested_near_parallel_cones.json"));
  const CaseModel m = build_case_model(c, 1e-5);
  long needed = -1;
  for (const bool full : {true, false}) {
    DistanceOptions o;
    // A leaf pair holds at most 2 x 2 arc pairs: a budget 5 below what the
    // full query needs stops it (within 4 of the budget) before it is done.
    if (!full) o.max_patch_pairs = needed - 5;
    const long budget = o.max_patch_pairs;
    const SolidDistanceResult r = solid_distance(m.instances[0], m.instances[1], o);
    std::printf("[ query    ] budget %ld: [%.17g, %.17g] %ld node pairs, %ld patch pairs: %s\n", budget, r.lower, r.upper,
                r.stats.node_pairs, r.stats.patch_pairs, r.reason.c_str());
    SCOPED_TRACE("max_patch_pairs " + std::to_string(budget) + ": " + r.reason);
    if (full) {
      ASSERT_TRUE(r.converged);
      needed = r.stats.patch_pairs;
      ASSERT_GE(needed, 6) << "the case no longer needs kernels: the budget is not exercised";
    } else {
      EXPECT_FALSE(r.converged);
      EXPECT_NE(r.reason.find("max_patch_pairs"), std::string::npos);
    }
    EXPECT_LE(r.stats.patch_pairs, budget + 4);
    EXPECT_LE(r.lower, 0.099984933);
    EXPECT_GE(r.upper, 0.099984462);
    EXPECT_LE(r.upper, 0.1);
  }
}

// Each budget names itself, and the bracket at the stop is finite and ordered.
TEST(WorkBudget, EachBudgetSaysWhatRanOut) {
  // (The paper's pairs need no enumeration at this tol since the local proof
  // hands back the nearest box centre it saw; the nested cones need 21.)
  const Case c = read_case(source("cases/regressions/budget_nested_near_parallel_cones.json"));
  const CaseModel m = build_case_model(c, 1e-5);
  DistanceOptions full;
  full.tol = 1e-9;
  // The first query whose reference needs kernels (the enumeration) to meet
  // tol, so that a budget of one runs out.
  std::size_t q = 0;
  SolidDistanceResult ref;
  for (; q < c.queries.size(); ++q) {
    ref = solid_distance(m.instances[c.queries[q].first], m.instances[c.queries[q].second], full);
    if (ref.stats.patch_pairs >= 2) break;
  }
  ASSERT_LT(q, c.queries.size());
  ASSERT_TRUE(ref.converged) << ref.reason;
  const auto [ia, ib] = c.queries[q];
  for (const std::string budget : {"max_node_pairs", "max_patch_pairs", "max_leaf_pairs"}) {
    DistanceOptions o = full;
    const bool kernels = budget == "max_patch_pairs";
    if (kernels) o.max_patch_pairs = 1;
    else if (budget == "max_leaf_pairs") o.max_leaf_pairs = 2;
    else o.max_node_pairs = 20;
    const SolidDistanceResult r = solid_distance(m.instances[ia], m.instances[ib], o);
    SCOPED_TRACE(r.reason);
    EXPECT_FALSE(r.converged);
    EXPECT_NE(r.reason.find(budget), std::string::npos);
    if (budget == "max_leaf_pairs") { EXPECT_LE(r.stats.leaf_pairs, 2); }
    EXPECT_TRUE(std::isfinite(r.lower) && std::isfinite(r.upper));
    EXPECT_LE(r.lower, r.upper);
    // Both brackets hold the distance (the reference is 1e-9 wide).
    EXPECT_LE(r.lower, ref.upper);
    EXPECT_GE(r.upper, ref.lower);
    if (kernels) { EXPECT_LE(r.stats.patch_pairs, 1 + 4); }
    else if (budget == "max_node_pairs") { EXPECT_LE(r.stats.node_pairs, 21); }
  }
}

}  // namespace
}  // namespace revdist
