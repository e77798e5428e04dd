// `revdist compare` as a library (compare/compare.h): on closed-form cases every
// fast bracket holds against the certified distance, FCL stays within 2 eps, the
// outputs are all there; and a deliberately wrong engine (an eps dropped from
// the lower bound) shows up as bound violations.
#include <gtest/gtest.h>

#include <string>

#include "compare/compare.h"

namespace revdist {
namespace {

std::string src(const std::string& rel) { return std::string(REVDIST_SOURCE_DIR) + "/" + rel; }

CompareOptions quick() {
  CompareOptions o;
  o.eps = {1e-3};
  o.tol = {1e-6};
  o.repeat = 1;
  o.frames = 1;
  o.arc_model = false;
  return o;
}

TEST(Compare, ClosedFormCasesHoldAndWriteEveryFile) {
  const CompareOutput out = run_compare({src("cases/distance/two_spheres.json"), src("cases/distance/nested.json")}, quick());
  EXPECT_EQ(out.bound_violations, 0);
  for (const char* f : {"compare.csv", "compare.json", "report.md", "time_vs_error.svg", "width_vs_eps.svg",
                        "width_vs_tol.svg", "memory_vs_eps.svg", "error_cdf.svg"})
    EXPECT_TRUE(out.files.count(f)) << f;
  const nlohmann::json j = nlohmann::json::parse(out.files.at("compare.json"));
  long fast = 0, fcl = 0;
  for (const auto& r : j["rows"]) {
    if (r["method"] == "fast") {
      ++fast;
      EXPECT_EQ(r["bound_held"], "yes") << r.dump();
    }
    if (r["method"] == "fcl") {
      ++fcl;
      // nested.json holds one solid inside another: FCL's surface distance is not the solid distance.
      if (r["exact_upper"].get<double>() > 0) {
        EXPECT_EQ(r["bound_held"], "yes") << r.dump();
      }
      EXPECT_GT(r["triangles"].get<long>(), 0);
    }
  }
  EXPECT_GT(fast, 0);
  EXPECT_EQ(fast, fcl);  // one tol: a fast row for every FCL row
  EXPECT_NE(out.files.at("report.md").find("surfaces, not solids"), std::string::npos);
}

TEST(Compare, DroppedEpsInTheLowerBoundShowsAsViolations) {
  StressEngines mutant;
  mutant.solid = [](const PosedSolid& a, const PosedSolid& b, const DistanceOptions& o) {
    SolidDistanceResult r = solid_distance(a, b, o);
    r.lower += 1e-3;  // the fit eps of this run, dropped from the lower bound
    r.upper = std::max(r.upper, r.lower);
    r.distance = 0.5 * (r.lower + r.upper);
    return r;
  };
  const CompareOutput out = run_compare({src("cases/distance/two_spheres.json")}, quick(), mutant);
  // Every fast row: each query in the case's frame and one random frame.
  long fast = 0;
  const nlohmann::json j = nlohmann::json::parse(out.files.at("compare.json"));
  for (const auto& r : j["rows"]) fast += r["method"] == "fast";
  EXPECT_GT(fast, 0);
  EXPECT_EQ(out.bound_violations, fast);
}

}  // namespace
}  // namespace revdist
