// Instance motion over scene frames (core/motion.h) and its reading from a
// revdist/1 case: closed forms, frame 0 = the given pose, bad motions rejected.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

#include "core/case_io.h"
#include "core/input_error.h"
#include "core/motion.h"

namespace revdist {
namespace {

TEST(Motion, FramesFollowTheClosedForms) {
  Pose p0;
  p0.q = {0.9, 0.1, -0.3, 0.2};  // not unit: M(q)/|q|^2 still a rotation
  p0.translation = Vec3(1, 2, 3);
  InstanceMotion m;
  m.velocity = Vec3(0.5, 0, 0);
  m.acceleration = Vec3(0, 0, -2);
  m.spin = Vec3(0, 0.1, 0.2);
  m.wave_amplitude = Vec3(0, 1, 0);
  m.wave_period = 8;
  m.wave_phase = 0.4;
  const Pose at0 = pose_at_frame(p0, m, 0);
  EXPECT_EQ(at0.translation, p0.translation);
  EXPECT_EQ(at0.q, p0.q);
  const double f = 3;
  const Pose p = pose_at_frame(p0, m, f);
  const double wave = std::sin(2 * M_PI * f / 8 + 0.4) - std::sin(0.4);
  const Vec3 want_t = Vec3(1 + 1.5, 2 + wave, 3 - 9);
  // A few ulps of the coordinates: sums of three terms.
  EXPECT_LE((p.translation - want_t).norm(), 16 * DBL_EPSILON * 10);
  const Mat3 want_R = Eigen::AngleAxisd(m.spin.norm() * f, m.spin.normalized()).toRotationMatrix() * p0.rotation();
  // Quaternion product and normalisation: a few ulps of unit entries.
  EXPECT_LE((p.rotation() - want_R).cwiseAbs().maxCoeff(), 64 * DBL_EPSILON);
}

std::string write_case(const std::string& motion) {
  // One file per process: ctest runs the tests of this binary in parallel.
  const std::string path = testing::TempDir() + "revdist_motion_test_" + std::to_string(getpid()) + ".json";
  std::ofstream(path) << R"({"format": "revdist/1", "solids": {"ball": {"profile": [{"arc": [[0,-1],[1,0],[0,1]]}]}},
    "instances": [{"name": "a", "solid": "ball", "motion": )" << motion << R"(}, {"name": "b", "solid": "ball"}]})";
  return path;
}

TEST(Motion, ReadFromTheCase) {
  const Case c = read_case(write_case(R"({"velocity": [1,0,0], "spin": [0,0,0.5], "wave": {"amplitude": [0,0,1], "period": 4}})"));
  EXPECT_EQ(c.instances[0].motion.velocity, Vec3(1, 0, 0));
  EXPECT_EQ(c.instances[0].motion.spin, Vec3(0, 0, 0.5));
  EXPECT_EQ(c.instances[0].motion.wave_period, 4.0);
  EXPECT_TRUE(c.instances[0].motion.moving());
  EXPECT_FALSE(c.instances[1].motion.moving());
  // Without queries: all pairs, unless the reader is told the broad phase will find them.
  EXPECT_EQ(c.queries.size(), 1u);
  EXPECT_TRUE(read_case(write_case("{}"), false).queries.empty());
}

TEST(Motion, BadMotionIsAnInputErrorNamingTheInstance) {
  for (const char* bad : {R"({"velocity": [1,0]})", R"({"wave": {"amplitude": [0,0,1], "period": 0}})",
                          R"({"sway": [0,0,1]})", R"([1,2,3])", R"({"spin": [0,"x",0]})"}) {
    try {
      read_case(write_case(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("instance \"a\" motion"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace revdist
