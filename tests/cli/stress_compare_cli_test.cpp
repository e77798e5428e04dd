// End-to-end checks of `revdist stress` and `revdist compare`: usage errors exit
// 2 with one line, the SPEC section 5 stress keys, shards merged through files
// equal the unsharded run, worst cases reload, compare writes its report.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace {

using revdist_test::CommandRun;
using revdist_test::run;

std::string src(const std::string& rel) { return std::string(REVDIST_SOURCE_DIR) + "/" + rel; }
std::string tmp(const std::string& name) { return testing::TempDir() + "revdist_sc_" + std::to_string(getpid()) + "_" + name; }

nlohmann::json without_times(nlohmann::json j) {
  j.erase("run");
  j.erase("shard");
  j["totals"].erase("time_s");
  for (auto& f : j["families"]) f.erase("time_s");
  return j;
}

TEST(StressCli, UsageErrorsExitTwoWithOneLine) {
  for (const char* args : {"stress --family nope --n 2", "stress --family all --n 2 --shard 3/2",
                           "stress --family all --n 2 --shard x", "stress --n 2", "stress --merge /no/such/file.json"}) {
    const CommandRun r = run(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  const CommandRun r = run("stress --family nope --n 2");
  EXPECT_NE(r.err.find("nope"), std::string::npos) << r.err;
}

TEST(StressCli, JsonKeysShardsMergeAndWorstCasesReload) {
  const std::string common = " --family circle_coaxial --family tangent_touching --family containment --n 5 --seed 5"
                             " --exact-every 0 --circle-exact-every 2 --json";
  const CommandRun whole = run("stress" + common);
  ASSERT_EQ(whole.status, 0) << whole.err;
  const nlohmann::json w = nlohmann::json::parse(whole.out);
  ASSERT_EQ(w["families"].size(), 3u);
  for (const auto& f : w["families"]) {
    for (const char* k : {"name", "n", "violations", "max_abs_error", "max_rel_error", "nans", "not_converged", "time_s"})
      EXPECT_TRUE(f.contains(k)) << k;
    EXPECT_EQ(f["n"], 5);
    EXPECT_EQ(f["violations"], 0) << f.dump();
  }
  std::string files;
  for (int k = 1; k <= 2; ++k) {
    const CommandRun s = run("stress" + common + " --shard " + std::to_string(k) + "/2");
    ASSERT_EQ(s.status, 0) << s.err;
    const std::string path = tmp("shard_" + std::to_string(k) + ".json");
    std::ofstream(path) << s.out;
    files += " " + path;
  }
  const std::string dir = tmp("worst");
  const CommandRun m = run("stress --merge" + files + " --json --save-worst " + dir);
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_EQ(without_times(nlohmann::json::parse(m.out)), without_times(w));
  int saved = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    ++saved;
    const bool circle = e.path().filename().string().rfind("stress_circle_", 0) == 0;
    const CommandRun d = run(std::string(circle ? "circles " : "distance ") + e.path().string());
    EXPECT_EQ(d.status, 0) << e.path() << ": " << d.err;
  }
  EXPECT_EQ(saved, 3);
  std::filesystem::remove_all(dir);
}

TEST(CompareCli, WritesTheReportAndRejectsBadInput) {
  const std::string dir = tmp("compare");
  const CommandRun r = run("compare " + src("cases/distance/two_spheres.json") +
                    " --eps 1e-3 --tol 1e-6,1e-8 --repeat 1 --frames 0 --no-arc-model --out " + dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("fast bound violations: 0"), std::string::npos) << r.out;
  for (const char* f : {"compare.csv", "compare.json", "report.md", "time_vs_error.svg", "error_cdf.svg"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + std::string(f))) << f;
  std::filesystem::remove_all(dir);
  EXPECT_EQ(run("compare /no/such/case.json --out " + dir).status, 2);
  EXPECT_EQ(run("compare " + src("cases/distance/two_spheres.json") + " --eps -1 --out " + dir).status, 2);
  EXPECT_EQ(run("compare " + src("cases/bad/not_closed.json") + " --out " + dir).status, 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/report.md"));
}

}  // namespace
