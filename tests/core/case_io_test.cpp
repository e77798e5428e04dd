// revdist/1 reading: every bundled model reads; every file in cases/bad fails with one
// line naming the file and the item; keyframe blending.
#include "core/case_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/curve_eval.h"
#include "core/input_error.h"
#include "core/profile_check.h"

namespace revdist {
namespace {

namespace fs = std::filesystem;
const std::string kSource = REVDIST_SOURCE_DIR;

std::vector<std::string> json_files(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(kSource + "/" + dir))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(CaseIo, EveryModelReads) {
  const auto files = json_files("cases/models");
  ASSERT_GE(files.size(), 10u);
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    Case c;
    ASSERT_NO_THROW(c = read_case(f)) << [&] {
      try { read_case(f); } catch (const std::exception& e) { return std::string(e.what()); }
      return std::string();
    }();
    EXPECT_FALSE(c.instances.empty());
    EXPECT_FALSE(c.queries.empty());
  }
}


// Each file in cases/bad and a fragment its one-line message must contain.
const std::map<std::string, std::string> kBad = {
    {"arc_bulging_past_its_points", R"(solid "s" piece 0: arc points coincide)"},
    {"arc_collinear", R"(solid "can" piece 1: arc points are collinear)"},
    {"bad_degree", R"(solid "vase" piece 0: degree 2.5)"},
    {"bezier_cusp", R"(solid "s" piece 0: the curve stops at parameter 0.5, at (1, 0.75))"},
    {"blend_self_intersecting", R"(instance "a" (solid "morph" at time 0.5): self-intersecting)"},
    {"bspline_end_knot_repeated", R"(solid "s" piece 0: an end knot is repeated more than degree + 1 = 2 times)"},
    {"bspline_knot_count", R"(solid "vase" piece 0: degree 3 with 5 points needs 9 knots, got 8)"},
    {"bspline_too_few_points", R"(solid "vase" piece 1: degree 3 needs at least 4 points)"},
    {"duplicate_instance", R"(instance "a": duplicate instance name)"},
    {"fold_back", R"(solid "spike": self-intersecting profile: pieces 1 and 2 fold back)"},
    {"infinity", R"(number overflow)"},
    {"keyframes_mismatch", R"(solid "morph" keyframe 1 piece 1: degree 3 with 4 points)"},
    {"knots_decreasing", R"(solid "vase" piece 0: knots decrease)"},
    {"knots_not_clamped", R"(solid "vase" piece 0: knots not clamped)"},
    {"loop_crosses_axis", R"(solid "ring" piece 1: closed loop touches or crosses the axis)"},
    {"loop_touches_axis", R"(solid "ring" piece 1: closed loop touches or crosses the axis)"},
    {"missing_format", R"(missing "format")"},
    {"nan_string", R"(solid "can" piece 1 point 1[1]: expected a finite number)"},
    {"negative_r_arc", R"(solid "bulge" piece 1: negative r)"},
    {"negative_r_curve", R"(solid "lens" piece 1: negative r)"},
    {"negative_r_point", R"(solid "can" piece 1: negative r)"},
    {"not_closed", R"(solid "cup": the profile neither reaches the axis at both ends nor closes)"},
    {"not_json", R"(not JSON)"},
    {"pieces_not_joined", R"(solid "can" piece 1: does not join piece 0)"},
    {"self_intersecting", R"(solid "knot": self-intersecting profile: pieces 1 and 3 meet)"},
    {"self_intersecting_piece", R"(solid "loop": self-intersecting profile: piece 1 meets itself)"},
    {"time_on_static", R"(instance "a": time 0.5 given for static solid "can")"},
    {"time_out_of_range", R"(instance "a": time 1.5 outside [0, 1])"},
    {"unknown_instance_query", R"(queries[1]: unknown instance "c")"},
    {"unknown_piece", R"(solid "ring" piece 1: unknown piece type "circle")"},
    {"unknown_solid", R"(instance "b": unknown solid "cna")"},
    {"weight_nonpositive", R"(solid "vase" piece 2: weight -1 <= 0)"},
    {"wrong_format", R"(format: expected "revdist/1")"},
    {"wrong_point_count", R"(solid "can" piece 0: a line needs 2 points, got 3)"},
    {"zero_quaternion", R"(instance "a" rotation: the zero quaternion)"},
    {"blend_arc_collinear", R"(instance "m" (solid "morph" at time 0.66666666666666663) piece 1: arc points are collinear)"},
    {"duplicate_member_key", R"(instances[1].translation: duplicate key "translation")"},
    {"duplicate_solid_key", R"(solids.s: duplicate key "s")"},
    {"name_with_newline", R"(queries[0]: unknown instance "b\nY")"},
    {"profile_scaled_1e300", R"(solid "big" piece 0: coordinate 1e+300 beyond the supported range)"},
    {"profile_too_far_off", R"(solid "ring": the profile (size 2.8284271247461903) lies 100000001 from the origin)"},
    {"repeated_end_point", R"(solid "s" piece 0: the last two control points coincide)"},
    {"translation_overflow", R"(instance "b" translation: component 1e+300 beyond the supported range)"},
    {"weight_ratio_huge", R"(solid "s" piece 0: weights 1 and 1e+300 differ by more than a factor 10000)"},
    {"weight_ratio_tiny", R"(solid "s" piece 0: weights 1e-300 and 1 differ by more than a factor 10000)"},
};

TEST(CaseIo, EveryBadFileFailsWithOneNamedLine) {
  const auto files = json_files("cases/bad");
  EXPECT_EQ(files.size(), kBad.size()) << "every bad case needs an expected message here";
  for (const std::string& f : files) {
    const std::string stem = fs::path(f).stem().string();
    SCOPED_TRACE(stem);
    ASSERT_TRUE(kBad.count(stem)) << "no expected message for " << f;
    try {
      read_case(f);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
      EXPECT_EQ(m.rfind(f + ": ", 0), 0u) << m;
      EXPECT_NE(m.find(kBad.at(stem)), std::string::npos) << m;
    }
  }
}

TEST(CaseIo, MissingFileIsInputError) {
  EXPECT_THROW(read_case(kSource + "/cases/bad/no_such_file.json"), InputError);
}

TEST(CaseIo, AllPairsWhenQueriesAbsentAndPaperPairs) {
  const Case c = read_case(kSource + "/cases/models/paper_pairs.json");
  EXPECT_EQ(c.solids.size(), 5u);
  EXPECT_EQ(c.queries.size(), 15u);
}

// Absent queries mean all pairs, up to kMaxAllPairs of them: 448 instances
// make 100128 pairs, refused in one line before any is listed (20000 made 2e8,
// and std::bad_alloc); 447 make 99681. A scene's reader lists none.
TEST(CaseIo, AllPairsAreCappedWhenQueriesAbsent) {
  auto text = [](int n) {
    std::string t = R"({"format": "revdist/1", "solids": {"s": {"profile": [{"arc": [[0, -1], [1, 0], [0, 1]]}]}}, "instances": [)";
    for (int i = 0; i < n; ++i)
      t += (i ? ", " : "") + std::string(R"({"name": "i)") + std::to_string(i) + R"(", "solid": "s", "translation": [)" +
           std::to_string(3 * i) + ", 0, 0]}";
    return t + "]}";
  };
  EXPECT_EQ(read_case_text(text(447), "ok.json").queries.size(), 99681u);
  try {
    read_case_text(text(448), "many.json");
    ADD_FAILURE() << "448 instances without queries were read";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("many.json: instances: 448 instances and no \"queries\": all 100128 pairs"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

// Accuracy review: a quaternion whose |q|^2 underflows is still a rotation
// (it was refused as the zero quaternion), and a piece on the far side of the
// axis is reported as negative r (it was "lies on the axis").
TEST(CaseIo, TinyQuaternionIsItsRotationAndAFarSidePieceIsNegativeR) {
  auto with_rotation = [](const std::string& q) {
    return R"({"format": "revdist/1", "solids": {"s": {"profile": [{"arc": [[0, -1], [1, 0], [0, 1]]}]}},
               "instances": [{"name": "a", "solid": "s", "rotation": )" + q + R"(}, {"name": "b", "solid": "s"}]})";
  };
  const Case tiny = read_case_text(with_rotation("[1e-170, 1e-170, 0, 0]"), "tiny.json");
  const Case unit = read_case_text(with_rotation("[1, 1, 0, 0]"), "unit.json");
  EXPECT_EQ(tiny.instances[0].pose.rotation(), unit.instances[0].pose.rotation());
  EXPECT_THROW(read_case_text(with_rotation("[0, 0, 0, 0]"), "zero.json"), InputError);
  try {
    read_case_text(R"({"format": "revdist/1", "solids": {"s": {"profile": [{"arc": [[0, 2], [-2, 0], [0, -2]]}]}},
                       "instances": [{"name": "a", "solid": "s"}]})",
                   "far.json");
    ADD_FAILURE() << "a profile at r < 0 was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("negative r: r <= 0 throughout, down to r = -2"), std::string::npos) << e.what();
  }
}

TEST(CaseIo, ProfileAtBlendsKeyframes) {
  const Case c = read_case(kSource + "/cases/models/morph.json");
  const SolidDef& s = c.solids.at(0);
  ASSERT_EQ(s.keyframes.size(), 5u);
  // Integer times are exactly the keyframes; half-way is the average of the control points.
  const Profile p1 = profile_at(s, 1.0), p2 = profile_at(s, 2.0), mid = profile_at(s, 1.5);
  for (std::size_t i = 0; i < mid.pieces.size(); ++i)
    for (std::size_t j = 0; j < mid.pieces[i].points.size(); ++j) {
      EXPECT_EQ(p1.pieces[i].points[j], s.keyframes[1].pieces[i].points[j]);
      const Vec2 avg = 0.5 * (p1.pieces[i].points[j] + p2.pieces[i].points[j]);
      EXPECT_NEAR((mid.pieces[i].points[j] - avg).norm(), 0.0, 1e-15);
    }
  // Joins stay exact in a blend: blends of equal points are equal.
  for (std::size_t i = 1; i < mid.pieces.size(); ++i) EXPECT_EQ(mid.pieces[i].start(), mid.pieces[i - 1].end());
  EXPECT_EQ(profile_at(s, 99.0).pieces[1].points, s.keyframes[4].pieces[1].points);  // clamped
}

TEST(CaseIo, JoinsSnapAndTolerance) {
  // A gap of 1e-12 on a profile of size ~2 is within the 1e-9 relative tolerance and is closed.
  const std::string path = testing::TempDir() + "/revdist_snap.json";
  std::ofstream(path) << R"({"format":"revdist/1","solids":{"can":{"profile":[
    {"line":[[0,0],[0.5,0]]},{"line":[[0.5,1e-12],[0.5,2]]},{"line":[[0.5,2],[1e-12,2]]}]}}})";
  const Case c = read_case(path);
  const Profile& p = c.solids[0].keyframes[0];
  EXPECT_EQ(p.pieces[1].start(), p.pieces[0].end());
  EXPECT_EQ(p.pieces[2].end().x(), 0.0);
  EXPECT_FALSE(p.closed_loop);
  EXPECT_TRUE(c.instances.empty());
  EXPECT_TRUE(read_case(kSource + "/cases/models/torus.json").solids[0].keyframes[0].closed_loop);
}

}  // namespace
}  // namespace revdist
