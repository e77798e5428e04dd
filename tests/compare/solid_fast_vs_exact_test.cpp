// The exact engine as the oracle of the fast one on solids (issue 4): every query
// of every bundled model case (cases/models/*.json), each registered as its own
// test. Both engines claim an interval holding the true distance d, so:
//   - the intervals must meet (fast.lower <= exact.upper, exact.lower <= fast.upper);
//     a gap is a proven bound violation of one of them;
//   - fast's witness pair is genuine, so |point_a - point_b| >= exact.lower
//     (up to the double rounding of the points);
//   - overlap flags agree when either engine proves overlap.
// fast's "distance" is the middle of its interval, not |point_a - point_b|, so it
// may lie (by < tol) below the exact interval; it is not compared directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/case_io.h"
#include "exact/solid_distance_exact.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist {
namespace {

constexpr double kEps = 1e-5;  // fit bound of the fast trees
constexpr double kTol = 1e-9;  // fast's target width, and exact's relative width

void check_query(const std::string& path, std::size_t q) {
  const Case c = read_case(path);
  const CaseModel model = build_case_model(c, kEps);
  const auto [ia, ib] = c.queries[q];
  DistanceOptions fo;
  fo.tol = kTol;
  const SolidDistanceResult f = solid_distance(model.instances[ia], model.instances[ib], fo);
  const Instance& A = c.instances[ia];
  const Instance& B = c.instances[ib];
  const ExactSolidResult x = solid_distance_exact(profile_at(c.solids[A.solid], A.time), A.pose,
                                                  profile_at(c.solids[B.solid], B.time), B.pose);
  std::printf("%s %s-%s: exact [%.17g, %.17g] width %.2g (%ld boxes, %.1f ms); fast [%.17g, %.17g]\n",
              std::filesystem::path(path).filename().c_str(), A.name.c_str(), B.name.c_str(), x.lower, x.upper,
              x.upper - x.lower, x.boxes, x.time_ms, f.lower, f.upper);
  ASSERT_TRUE(x.certified) << x.reason;
  EXPECT_TRUE(x.width_reached) << x.reason;
  EXPECT_LE(f.lower, x.upper) << "fast's lower bound exceeds the proven upper bound";
  EXPECT_LE(x.lower, f.upper) << "fast's upper bound is below the proven lower bound";
  if (!f.overlap) {
    // Rounding of the witness coordinates: a few ulps of the largest one.
    const double coord = std::max(f.point_a.cwiseAbs().maxCoeff(), f.point_b.cwiseAbs().maxCoeff());
    EXPECT_GE((f.point_a - f.point_b).norm(), x.lower - 8 * coord * 2.220446049250313e-16);
  }
  if (x.overlap || f.overlap) {
    EXPECT_EQ(x.overlap, f.overlap);
  }
}

std::vector<std::pair<std::string, std::size_t>> model_queries() {
  std::vector<std::pair<std::string, std::size_t>> out;
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(REVDIST_SOURCE_DIR) + "/cases/models"))
    if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) {
    const Case c = read_case(f);
    for (std::size_t q = 0; q < c.queries.size(); ++q) out.emplace_back(f, q);
  }
  return out;
}

class SolidFastVsExact : public testing::Test {
 public:
  SolidFastVsExact(std::string path, std::size_t q) : path_(std::move(path)), q_(q) {}
  void TestBody() override { check_query(path_, q_); }

 private:
  std::string path_;
  std::size_t q_;
};

// One named test per query (manifold's habit): a failure names its case.
const bool kRegistered = [] {
  for (const auto& [path, q] : model_queries()) {
    const std::string name = std::filesystem::path(path).stem().string() + "_q" + std::to_string(q);
    testing::RegisterTest("SolidFastVsExact", name.c_str(), nullptr, nullptr, __FILE__, __LINE__,
                          [path = path, q = q]() -> testing::Test* { return new SolidFastVsExact(path, q); });
  }
  return true;
}();

}  // namespace
}  // namespace revdist
