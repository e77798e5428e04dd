// The near-contact motion of the benchmarks (compare/motion.h): the gap follows
// its plan, the motion is continuous, and the planned overlaps really overlap.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "compare/bench_paper.h"
#include "compare/motion.h"
#include "core/input_error.h"
#include "core/case_io.h"
#include "fast/biarc_tree.h"

namespace revdist {
namespace {

std::uint64_t test_seed() {
  const char* s = std::getenv("REVDIST_SEED");
  const std::uint64_t seed = s ? std::strtoull(s, nullptr, 10) : 7;
  std::printf("REVDIST_SEED=%llu\n", static_cast<unsigned long long>(seed));
  return seed;
}

const SolidDef& solid(const Case& c, const std::string& name) {
  for (const SolidDef& s : c.solids)
    if (s.name == name) return s;
  throw std::runtime_error("no solid " + name);
}

TEST(NearContactMotion, GapFollowsPlanAndMotionIsContinuous) {
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/models/paper_pairs.json");
  const Profile pa = profile_at(solid(c, "cup"), 0), pb = profile_at(solid(c, "lightmil"), 0);
  const BiarcTree ta = build_biarc_tree(pa, 1e-5), tb = build_biarc_tree(pb, 1e-5);
  PosedSolid A{&pa, &ta}, B{&pb, &tb};
  MotionOptions o;
  o.frames = 24;
  o.seed = test_seed();
  const std::vector<MotionFrame> frames = near_contact_motion(A, [&](int) { return B; }, o);
  ASSERT_EQ(frames.size(), 24u);
  const double size = std::max(profile_extent(pa), profile_extent(pb));
  const double delta = o.clearance * size;
  int planned_overlaps = 0, evaluations = 0;
  for (std::size_t j = 0; j < frames.size(); ++j) {
    const MotionFrame& f = frames[j];
    evaluations += f.evaluations;
    // Rotations stay orthonormal to rounding (products of a few rotations: 1e-14 is ~50 ulps).
    EXPECT_LT((f.R_WA * f.R_WA.transpose() - Mat3::Identity()).norm(), 1e-14);
    EXPECT_LT((f.R_WB * f.R_WB.transpose() - Mat3::Identity()).norm(), 1e-14);
    EXPECT_LE(f.target, delta * (1 + o.swing) * (1 + 1e-12));
    A.R = f.R_WA, A.t = f.t_WA, B.R = f.R_WB, B.t = f.t_WB;
    const SolidDistanceResult r = solid_distance(A, B, DistanceOptions{1e-3 * delta});
    if (f.target >= 0.15 * delta) {
      // The solver accepts 5 % of delta; the check's own bracket is 0.1 %.
      EXPECT_NEAR(r.distance, f.target, 0.051 * delta) << "frame " << j;
    } else if (f.target < -0.01 * delta) {
      ++planned_overlaps;
      // Solved to a gap of 0.15 delta (+- 0.05), then pushed in along the approach: closer than that.
      EXPECT_LE(r.lower, 0.2 * delta) << "frame " << j;
    }
    if (j > 0) {
      // 24 frames of one slow revolution: b moves by much less than the pair's size per frame.
      EXPECT_LT((f.t_WB - frames[j - 1].t_WB).norm(), 0.6 * size) << "frame " << j;
    }
  }
  std::printf("planned overlaps %d of %zu, setup queries %.1f per frame\n", planned_overlaps, frames.size(),
              double(evaluations) / frames.size());
  EXPECT_LT(evaluations, 30 * static_cast<int>(frames.size()));
}

TEST(NearContactMotion, SameSeedSameFrames) {
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/models/paper_pairs.json");
  const Profile p = profile_at(solid(c, "pawn"), 0);
  const BiarcTree t = build_biarc_tree(p, 1e-4);
  const PosedSolid A{&p, &t};
  MotionOptions o;
  o.frames = 4;
  const auto f1 = near_contact_motion(A, [&](int) { return A; }, o);
  const auto f2 = near_contact_motion(A, [&](int) { return A; }, o);
  for (std::size_t j = 0; j < f1.size(); ++j) EXPECT_EQ(f1[j].t_WB, f2[j].t_WB);
  o.seed = 2;
  const auto f3 = near_contact_motion(A, [&](int) { return A; }, o);
  EXPECT_NE(f1[1].t_WB, f3[1].t_WB);
}


// The poses file of `revdist bench --poses` (compare/bench_paper.h): the frames
// come back bit for bit, and anything else is refused with one line naming
// the file.
TEST(BenchPoses, RoundTripAndRefusals) {
  // Frames of any motion will do: rotations about skew axes, translations and
  // gaps with full mantissas.
  auto frames = [](double k) {
    std::vector<MotionFrame> f(5);
    for (int j = 0; j < 5; ++j) {
      f[j].R_WA = Eigen::AngleAxisd(0.1 * j + k, Vec3(1, 2, 3).normalized()).toRotationMatrix();
      f[j].R_WB = Eigen::AngleAxisd(1.0 / 3 + j, Vec3(-2, 1, 0.5).normalized()).toRotationMatrix();
      f[j].t_WA = Vec3(std::sqrt(2.0) * j, -k / 7, 1e-9 * j);
      f[j].t_WB = Vec3(M_PI, std::exp(k + j), -1.0 / 3);
      f[j].target = (j - 2) * 1e-3 / 3, f[j].achieved = std::max(f[j].target, 0.0), f[j].evaluations = 3 * j;
    }
    return f;
  };
  BenchPoses p;
  p.source = "paper", p.seed = 42, p.frames = 5;
  p.pairs.emplace_back("cup-pawn", frames(0.25));
  p.pairs.emplace_back("pawn-pawn", frames(1.5));
  const std::string bytes = encode_bench_poses(p);
  const BenchPoses q = decode_bench_poses(bytes, "f.bin");
  EXPECT_EQ(q.source, "paper");
  EXPECT_EQ(q.seed, 42u);
  EXPECT_EQ(q.frames, 5);
  ASSERT_EQ(q.pairs.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(q.pairs[k].first, p.pairs[k].first);
    ASSERT_EQ(q.pairs[k].second.size(), 5u);
    for (int j = 0; j < 5; ++j) {
      const MotionFrame &x = p.pairs[k].second[j], &y = q.pairs[k].second[j];
      EXPECT_EQ(std::memcmp(x.R_WA.data(), y.R_WA.data(), 9 * sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(x.R_WB.data(), y.R_WB.data(), 9 * sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(x.t_WA.data(), y.t_WA.data(), 3 * sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(x.t_WB.data(), y.t_WB.data(), 3 * sizeof(double)), 0);
      EXPECT_EQ(x.target, y.target);
      EXPECT_EQ(x.achieved, y.achieved);
      EXPECT_EQ(x.evaluations, y.evaluations);
    }
  }
  // Refusals: one line naming the file and the problem.
  auto refused = [](const std::string& b, const std::string& problem) {
    try {
      decode_bench_poses(b, "f.bin");
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("f.bin: ", 0), 0u) << m;
      EXPECT_NE(m.find(problem), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
      return;
    }
    ADD_FAILURE() << "accepted: " << problem;
  };
  refused("", "not a revdist-bench-poses/1 file");
  refused("revdist-bench-poses/2\n" + bytes.substr(22), "not a revdist-bench-poses/1 file");
  refused(bytes.substr(0, bytes.size() - 1), "truncated");
  refused(bytes.substr(0, 40), "truncated");
  refused(bytes + "x", "1 bytes after the last frame");
  // The first frame's first coordinate: after the magic, header and both names.
  const std::size_t first = 22 + 8 + 4 + 4 + 4 + 5 + 4 + 8 + 4;
  std::string nan = bytes;
  const double q_nan = std::nan("");
  std::memcpy(&nan[first], &q_nan, sizeof q_nan);
  refused(nan, "not finite");
  std::string skew = bytes;
  const double two = 2.0;
  std::memcpy(&skew[first], &two, sizeof two);
  refused(skew, "not orthonormal");
  BenchPoses mirrored = p;  // orthonormal, but a reflection
  mirrored.pairs[0].second[3].R_WB.col(0) *= -1;
  refused(encode_bench_poses(mirrored), "not orthonormal");
  BenchPoses negative = p;
  negative.pairs[1].second[0].achieved = -1e-3;
  refused(encode_bench_poses(negative), "a negative gap or evaluation count");
  BenchPoses unmeasured = p;
  unmeasured.pairs[1].second[4].achieved = NAN;
  refused(encode_bench_poses(unmeasured), "an achieved gap is not finite");
  BenchPoses r = p;
  r.pairs[1].second.pop_back();
  refused(encode_bench_poses(r), "holds 4 frames, the header says 5");
}

}  // namespace
}  // namespace revdist
