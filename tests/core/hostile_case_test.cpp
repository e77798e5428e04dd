// The case reader against hostile input (issue 10 items 4, 15, 17): strict JSON (depth,
// duplicate keys), one-line messages whatever names hold, subquadratic validation.
#include <gtest/gtest.h>
#include <time.h>

#include <cmath>
#include <string>

#include "core/case_io.h"
#include "core/input_error.h"
#include "core/json_util.h"
#include "core/profile_check.h"

namespace revdist {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_json_text(text, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileCase, DuplicateKeysAreRejectedAtAnyDepth) {
  EXPECT_NE(error_of(R"({"a": 1, "a": 2})").find("duplicate key \"a\""), std::string::npos);
  const std::string nested = error_of(R"({"solids": {"s": {"profile": [{"line": 1, "line": 2}]}}})");
  EXPECT_NE(nested.find("solids.s.profile[0]"), std::string::npos) << nested;
  // The same key in two different objects is fine.
  EXPECT_EQ(error_of(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 1}, {"x": 2}]})"), "");
}

TEST(HostileCase, NestingIsLimited) {
  EXPECT_EQ(error_of(std::string(63, '[') + std::string(63, ']')), "");
  const std::string e = error_of(std::string(100000, '[') + std::string(100000, ']'));
  EXPECT_NE(e.find("nested deeper than the limit of 64"), std::string::npos) << e.substr(0, 200);
  EXPECT_LT(e.size(), 200u);
}

TEST(HostileCase, QuotedNamesStayOnOneLine) {
  EXPECT_EQ(quote("a\nb\"c\\"), "\"a\\nb\\\"c\\\\\"");
  EXPECT_EQ(quote(std::string("\x01", 1)), "\"\\u0001\"");
  EXPECT_EQ(quote(std::string(200, 'x')).size(), 80u + 2 + 3);
}

double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

// A half circle of n line pieces from axis to axis.
Profile polyline_ball(int n) {
  Profile p;
  Vec2 prev(0, -1);
  for (int i = 1; i <= n; ++i) {
    const double t = M_PI * i / n;
    const Vec2 q = i == n ? Vec2(0, 1) : Vec2(std::sin(t), -std::cos(t));
    Piece piece;
    piece.points = {prev, q};
    p.pieces.push_back(piece);
    prev = q;
  }
  return p;
}

TEST(HostileCase, HundredThousandPiecesValidateInSeconds) {
  // All pairs took ~100 s here; the grid of bounding boxes makes it near-linear.
  Profile p = polyline_ball(100000);
  const double t0 = thread_seconds();
  join_profile(p, "ball");
  check_profile(p, "ball");
  const double s = thread_seconds() - t0;
  std::printf("100000 pieces validated in %.3f s CPU\n", s);
  EXPECT_LT(s, 10.0);
  // The grid still finds a crossing between pieces far apart in the chain: piece 500
  // leaves (1, 0) inwards and exits through the arc of pieces ~100-300.
  Profile bad = polyline_ball(1000);
  bad.pieces[500].points[1] = Vec2(0.3, -1.2);
  bad.pieces[501].points[0] = bad.pieces[500].points[1];
  join_profile(bad, "bad");
  EXPECT_THROW(check_profile(bad, "bad"), InputError);
}

}  // namespace
}  // namespace revdist
