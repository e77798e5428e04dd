// Smoke test of `revdist bench` (CI-sized: a few frames, one eps): exit status,
// the revdist-bench/1 records, the report files, and its usage errors.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

using revdist_test::CommandRun;
using revdist_test::run;

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string src(const std::string& rel) { return std::string(REVDIST_SOURCE_DIR) + "/" + rel; }

TEST(BenchCli, PaperSmokeWritesRecordsAndReport) {
  const std::filesystem::path out = testing::TempDir() + "revdist_bench_" + std::to_string(getpid());
  const CommandRun r = run("bench paper --frames 3 --eps 1e-3 --exact-frames 0 --json --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  // Progress goes to stderr as plain lines when it is not a terminal.
  EXPECT_NE(r.err.find("bench: motion pawn-cup eps 1e-03"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["format"], "revdist-bench/1");
  EXPECT_NE(doc["timing"].get<std::string>().find("CLOCK_THREAD_CPUTIME_ID"), std::string::npos);
  std::set<std::string> motion_pairs, builds, deforms;
  std::vector<double> sweep;
  for (const auto& x : doc["records"]) {
    for (const char* key : {"pair", "eps", "median_us", "p90_us", "fcl_median_us", "ratio", "nodes", "bytes"})
      EXPECT_TRUE(x.contains(key)) << key;
    const std::string e = x["experiment"];
    if (e == "sweep") {
      // revdist alone over the decades from --eps down to 1/100 of it, all 45 frames each.
      sweep.push_back(x["eps"].get<double>());
      EXPECT_EQ(x["pair"], "all");
      EXPECT_EQ(x["samples"].get<int>(), 45);
      EXPECT_GT(x["median_us"].get<double>(), 0);
      EXPECT_TRUE(x["fcl_median_us"].is_null());
      EXPECT_EQ(x["unconverged"].get<int>(), 0) << x;
      continue;
    }
    EXPECT_EQ(x["eps"].get<double>(), 1e-3);
    if (e == "motion") {
      // A proven overlap is an overlap: the reference (tol 1e-9) finds it too.
      EXPECT_LE(x["overlaps"].get<int>(), x["overlapping_frames"].get<int>()) << x;
      if (x["overlapping_frames"].get<int>() == 0) {
        EXPECT_TRUE(x["overlap_p99_us"].is_null()) << x;
      }
      motion_pairs.insert(x["pair"].get<std::string>());
      EXPECT_GT(x["median_us"].get<double>(), 0);
      EXPECT_GE(x["p90_us"].get<double>(), x["median_us"].get<double>());
      ASSERT_TRUE(x["fcl_median_us"].is_number()) << x;
      // The ratio is the same run's FCL median over revdist's (printed rounding aside).
      EXPECT_NEAR(x["ratio"].get<double>(), x["fcl_median_us"].get<double>() / x["median_us"].get<double>(),
                  1e-9 * x["ratio"].get<double>());
      EXPECT_GT(x["fcl_triangles"].get<long>(), 0);
      EXPECT_EQ(x["violations"].get<int>(), 0);
      EXPECT_EQ(x["samples"].get<int>(), x["pair"] == "all" ? 45 : 3);
      // The warm-started sequence of the same frames is timed too.
      EXPECT_GT(x["coherent_median_us"].get<double>(), 0) << x;
      EXPECT_GE(x["coherent_p90_us"].get<double>(), x["coherent_median_us"].get<double>()) << x;
      // The p99 on the frames revdist proved overlapping: a time where there are such frames.
      ASSERT_TRUE(x.contains("proven_overlap_p99_us")) << x;
      if (x["overlaps"].get<int>() > 0)
        EXPECT_GT(x["proven_overlap_p99_us"].get<double>(), 0) << x;
      else
        EXPECT_TRUE(x["proven_overlap_p99_us"].is_null()) << x;
    } else if (e == "build") {
      builds.insert(x["pair"].get<std::string>());
      EXPECT_GT(x["nodes"].get<long>(), 0);
      // An inscribed mesh at eps 1e-3 costs far more memory than the biarc tree.
      EXPECT_GT(x["fcl_bytes"].get<long>(), 10 * x["bytes"].get<long>()) << x;
      EXPECT_GT(x["fcl_bv_nodes"].get<long>(), x["fcl_triangles"].get<long>());
    } else if (e == "deform") {
      deforms.insert(x["pair"].get<std::string>());
      EXPECT_TRUE(x["fcl_median_us"].is_null());
      EXPECT_TRUE(x["coherent_median_us"].is_null());
    }
  }
  EXPECT_EQ(motion_pairs.size(), 16u);  // the 15 pairs (Mi, Mj), i <= j, and "all"
  ASSERT_EQ(sweep.size(), 3u);
  EXPECT_NEAR(sweep[0], 1e-3, 1e-18);
  EXPECT_NEAR(sweep[2], 1e-5, 1e-20);
  EXPECT_EQ(builds, (std::set<std::string>{"pawn", "cup", "bottle", "table", "lightmil", "Mt"}));
  EXPECT_EQ(deforms.size(), 5u);
  for (const char* f : {"bench.md", "bench.json", "fig8.svg", "fig9.svg", "fig12.svg"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  EXPECT_EQ(nlohmann::json::parse(read(out / "bench.json")), doc);
  const std::string md = read(out / "bench.md");
  EXPECT_NE(md.find("![Figure 12](fig12.svg)"), std::string::npos);
  EXPECT_NE(md.find("| lightmil | 1e-03 |"), std::string::npos);
  EXPECT_NE(md.find("## Query time against eps"), std::string::npos);
  EXPECT_NE(md.find("median growth eps 1e-03 -> 1e-05"), std::string::npos);
  const std::string svg = read(out / "fig12.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_GT(std::count(svg.begin(), svg.end(), '\n'), 45);  // bars of 16 groups x 3 series
  std::filesystem::remove_all(out);
}

TEST(BenchCli, CaseWithCertifiedSample) {
  // Two static solids: three pairs, one frame each checked by the certified engine.
  const std::filesystem::path out = testing::TempDir() + "revdist_bench_case_" + std::to_string(getpid());
  const CommandRun r =
      run("bench " + src("cases/distance/sphere_can.json") + " --frames 2 --eps 1e-3 --exact-frames 1 --json --out " +
          out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  int certified = 0;
  for (const auto& x : doc["records"]) {
    if (x["experiment"] != "motion" || x["pair"] == "all") continue;
    certified += x["exact_frames"].get<int>();
    EXPECT_EQ(x["violations"].get<int>(), 0) << x;
    // tol = 2 eps; the inscribed mesh is within eps of each surface.
    EXPECT_LE(x["max_err"].get<double>(), 2e-3) << x;
    EXPECT_LE(x["fcl_max_err"].get<double>(), 2.1e-3) << x;
  }
  EXPECT_GE(certified, 2);
  std::filesystem::remove_all(out);
}

// --poses: the first run writes the motion frames, the second reads them (the
// same poses for two builds), a run that does not match them is refused.
TEST(BenchCli, PosesFileWrittenThenReadThenRefusedForAnotherRun) {
  const std::string tmp = testing::TempDir() + "revdist_poses_" + std::to_string(getpid());
  const std::string poses = tmp + ".bin";
  std::filesystem::remove(poses);
  const std::string args = "bench paper --eps 1e-3 --exact-frames 0 --no-fcl --poses " + poses + " --out " + tmp;
  const CommandRun w = run(args + " --frames 2");
  ASSERT_EQ(w.status, 0) << w.err;
  EXPECT_NE(w.err.find("motion frames written to " + poses), std::string::npos) << w.err;
  ASSERT_TRUE(std::filesystem::exists(poses));
  const std::string bytes = read(poses);
  const CommandRun r = run(args + " --frames 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("motion frames from " + poses), std::string::npos) << r.err;
  EXPECT_EQ(read(poses), bytes);  // read, not rewritten
  // Refused, one line on stderr (the banner waits for the first progress
  // line) naming the file: another run's poses (its size is not this run's),
  // a file of the right size that is not a poses file, a file that cannot be
  // written (with the reason).
  auto last_line = [](const std::string& err) {
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    return err.substr(err.rfind('\n', err.size() - 2) + 1);
  };
  const CommandRun x = run(args + " --frames 3");
  EXPECT_EQ(x.status, 2);
  EXPECT_EQ(last_line(x.err).rfind("revdist: " + poses + ": poses of another run (", 0), 0u) << x.err;
  const std::string nowhere = tmp + "_no_such_dir/p.bin";
  const CommandRun w2 = run("bench paper --eps 1e-3 --exact-frames 0 --no-fcl --frames 2 --poses " + nowhere + " --out " + tmp);
  EXPECT_EQ(w2.status, 2);
  EXPECT_EQ(last_line(w2.err), "revdist: " + nowhere + ": cannot write (No such file or directory)\n") << w2.err;
  {
    std::ofstream f(poses, std::ios::binary | std::ios::trunc);
    f << std::string(bytes.size(), 'x');
  }
  const CommandRun y = run(args + " --frames 2");
  EXPECT_EQ(y.status, 2);
  EXPECT_EQ(last_line(y.err), "revdist: " + poses + ": not a revdist-bench-poses/1 file\n") << y.err;
  std::filesystem::remove(poses);
  std::filesystem::remove_all(tmp);
}

TEST(BenchCli, BadInputExitsTwo) {
  const std::string out = " --out " + testing::TempDir() + "revdist_bench_bad";
  EXPECT_EQ(run("bench " + src("cases/no-such-file.json") + out).status, 2);
  EXPECT_EQ(run("bench paper --eps 0" + out).status, 2);
  EXPECT_EQ(run("bench paper --eps 1e-3,x" + out).status, 2);
  EXPECT_EQ(run("bench paper --frames 0" + out).status, 2);
  EXPECT_EQ(run("bench paper --frames 1000000" + out).status, 2);  // (was accepted: hours)
  const CommandRun r = run("bench " + src("cases/bad/not_json.json") + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
