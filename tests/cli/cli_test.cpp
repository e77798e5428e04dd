// End-to-end checks of the `revdist` executable: exit statuses, one-line
// errors naming file and item, and the JSON keys of SPEC section 5.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <array>
#include <filesystem>
#include <vector>
#include <cmath>
#include <fstream>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace {

using revdist_test::CommandRun;
using revdist_test::run;

std::string src(const std::string& rel) { return std::string(REVDIST_SOURCE_DIR) + "/" + rel; }

TEST(Cli, HelpExitsZero) {
  EXPECT_EQ(run("--help").status, 0);
  EXPECT_EQ(run("circles --help").status, 0);
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("no-such-command").status, 2);
  EXPECT_EQ(run("circles " + src("cases/circles/coaxial.json") + " --engine nope").status, 2);
}

TEST(Cli, CirclesJsonHasSpecKeys) {
  for (const std::string engine : {"fast", "exact"}) {
    const CommandRun r = run("circles " + src("cases/circles/coplanar.json") + " --json --engine " + engine);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["format"], "revdist-circles-result/1");
    EXPECT_EQ(doc["engine"], engine);
    const auto input = nlohmann::json::parse(std::ifstream(src("cases/circles/coplanar.json")));
    ASSERT_EQ(doc["results"].size(), input["pairs"].size());
    for (std::size_t i = 0; i < doc["results"].size(); ++i) {
      const auto& res = doc["results"][i];
      for (const char* key : {"distance", "status", "point_a", "point_b", "binormals"})
        EXPECT_TRUE(res.contains(key)) << key;
      if (engine == "exact") {
        for (const char* key : {"lower", "upper", "decimal"}) EXPECT_TRUE(res.contains(key)) << key;
        EXPECT_LE(res["lower"].get<double>(), res["upper"].get<double>());
        EXPECT_GE(res["decimal"].get<std::string>().size(), 30u);
        const auto& expected = input["pairs"][i]["expected"];
        if (!expected.is_null()) {
          const double e = expected.get<double>();
          EXPECT_LE(res["lower"].get<double>(), e + 1e-14);
          EXPECT_GE(res["upper"].get<double>(), e - 1e-14);
        }
      }
    }
  }
}

TEST(Cli, CirclesBothReportsDifference) {
  const CommandRun r = run("circles " + src("cases/circles/villarceau.json") + " --json --engine both");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  for (const auto& res : doc["results"]) {
    EXPECT_TRUE(res.contains("fast"));
    EXPECT_TRUE(res.contains("exact"));
    EXPECT_LE(std::abs(res["difference"].get<double>()), 1e-10);
  }
}

// The table shows every pair's distance (the file's expected values, to the
// 6 significant digits a reader checks) and the binormal lines under it.
TEST(Cli, CirclesTableByDefault) {
  // Coaxial pairs: a continuum of lines; parallel planes: finitely many.
  for (const char* file : {"cases/circles/coaxial.json", "cases/circles/parallel_planes.json"}) {
    const CommandRun r = run(std::string("circles ") + src(file));
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(src(file));
    const nlohmann::json pairs = nlohmann::json::parse(in)["pairs"];
    const std::size_t table_end = r.out.find("binormal lines");
    ASSERT_NE(table_end, std::string::npos) << r.out;
    const std::string table = r.out.substr(0, table_end), lines = r.out.substr(table_end);
    int listed = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (!pairs[i].contains("expected") || !pairs[i]["expected"].is_number()) continue;
      char want[32];
      std::snprintf(want, sizeof want, "%.6g", pairs[i]["expected"].get<double>());
      // The full-precision distance starts with the 6 significant digits (rounding aside).
      EXPECT_NE(table.find(std::string(want).substr(0, 6)), std::string::npos) << file << " pair " << i << "\n" << table;
      ++listed;
      EXPECT_NE(lines.find("#" + std::to_string(i) + (pairs[i].value("infinitely_many", false) ? ": infinitely many" : " line 0:")),
                std::string::npos)
          << file << " pair " << i << "\n" << lines;
    }
    EXPECT_GT(listed, 5) << file;
  }
}

// --engine both: each engine's status and count are visible (the Villarceau rows
// read infinitely_many for fast and ok for exact, not one merged "ok").
TEST(Cli, CirclesBothShowsEachEngine) {
  const CommandRun r = run("circles " + src("cases/circles/villarceau.json") + " --engine both");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("fast status"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("exact status"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("infinitely_many"), std::string::npos) << r.out;
  const CommandRun j = run("circles " + src("cases/circles/random.json") + " --engine both --json");
  ASSERT_EQ(j.status, 0) << j.err;
  // The document outlives the loop (a range over a member of a temporary would not).
  const auto doc = nlohmann::json::parse(j.out);
  for (const auto& res : doc["results"]) {
    ASSERT_TRUE(res["fast"].contains("lines"));
    EXPECT_EQ(res["fast"]["lines"].size() >= res["fast"]["binormals"].get<std::size_t>(), true);
    for (const auto& l : res["fast"]["lines"]) EXPECT_GE(l["length"].get<double>(), res["fast"]["distance"].get<double>() * (1 - 1e-12));
  }
}

// Each bad file: exit 2, nothing on stdout, exactly one line on stderr naming the file.
class CliBadCircles : public testing::TestWithParam<std::string> {};

TEST_P(CliBadCircles, OneLineErrorExitTwo) {
  const std::string file = src("cases/circles/bad/" + GetParam() + ".json");
  const CommandRun r = run("circles " + file);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  std::printf("%s -> %s", GetParam().c_str(), r.err.c_str());
}

INSTANTIATE_TEST_SUITE_P(BadInput, CliBadCircles,
                         testing::Values("not_json", "infinite_radius", "negative_radius", "zero_normal",
                                         "short_center", "missing_b", "wrong_format", "string_radius",
                                         "does_not_exist"));

}  // namespace

namespace {

// revdist distance and fit on every malformed case: exit 2, nothing on stdout,
// one line on stderr naming the file.
class CliBadCases : public testing::TestWithParam<std::string> {};

TEST_P(CliBadCases, DistanceAndFitRejectWithOneLine) {
  const std::string file = src("cases/bad/" + GetParam() + ".json");
  for (const std::string cmd : {"distance ", "fit "}) {
    const CommandRun r = run(cmd + file);
    EXPECT_EQ(r.status, 2) << cmd;
    EXPECT_TRUE(r.out.empty()) << r.out;
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  }
}

std::vector<std::string> bad_cases() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(src("cases/bad")))
    if (e.path().extension() == ".json") out.push_back(e.path().stem().string());
  std::sort(out.begin(), out.end());
  return out;
}

INSTANTIATE_TEST_SUITE_P(BadCases, CliBadCases, testing::ValuesIn(bad_cases()),
                         [](const testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(Cli, DistanceJsonHasSpecKeysForBothEngines) {
  for (const std::string engine : {"fast", "exact"}) {
    const CommandRun r = run("distance " + src("cases/distance/two_spheres.json") + " --json --engine " + engine);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["format"], "revdist-result/1");
    EXPECT_EQ(doc["engine"], engine);
    for (const char* key : {"eps", "tol", "results"}) EXPECT_TRUE(doc.contains(key)) << key;
    const auto input = nlohmann::json::parse(std::ifstream(src("cases/distance/two_spheres.json")));
    ASSERT_FALSE(doc["results"].empty());
    for (const auto& res : doc["results"]) {
      for (const char* key : {"a", "b", "lower", "upper", "distance", "overlap", "converged", "point_a", "point_b",
                              "stats"})
        EXPECT_TRUE(res.contains(key)) << key;
      EXPECT_TRUE(res["stats"].contains("time_us"));
      const std::string q = res["a"].get<std::string>() + "-" + res["b"].get<std::string>();
      if (input.contains("expected") && input["expected"].contains(q)) {
        const double d = input["expected"][q].get<double>();
        EXPECT_LE(res["lower"].get<double>(), d + 1e-12) << q;
        EXPECT_GE(res["upper"].get<double>(), d - 1e-12) << q;
      }
    }
  }
}

// A stopped --json run is still one JSON document: every finished result, then
// "stopped" with the signal's name, and the process dies of that signal (a
// script can tell it from a complete run by both). 19,900 queries of 200 rings
// take tens of seconds, so the signal lands mid-run.
TEST(Cli, DistanceJsonStoppedBySignalIsOneDocument) {
  const std::string scene = testing::TempDir() + "revdist_stop_rings_" + std::to_string(getpid()) + ".json";
  ASSERT_EQ(run("scene-gen rings --n 200 --out " + scene).status, 0);
  for (const int sig : {SIGINT, SIGTERM}) {
    const std::string out = testing::TempDir() + "revdist_stop_out_" + std::to_string(getpid()) + ".json";
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      if (!std::freopen(out.c_str(), "w", stdout) || !std::freopen("/dev/null", "w", stderr)) _exit(127);
      execl(REVDIST_BINARY, REVDIST_BINARY, "distance", "--json", scene.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    // Wait for some results (at most 60 s), then stop the run.
    auto size = [&] {
      std::error_code ec;  // the child may not have opened the file yet
      const auto n = std::filesystem::file_size(out, ec);
      return ec ? 0 : n;
    };
    for (int i = 0; i < 600 && size() < 4000; ++i) usleep(100000);
    ASSERT_EQ(kill(pid, sig), 0);
    int st = 0;
    ASSERT_EQ(waitpid(pid, &st, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(st) && WTERMSIG(st) == sig) << "status " << st;
    std::ifstream in(out);
    const auto doc = nlohmann::json::parse(in);  // throws (fails) on a cut document
    EXPECT_EQ(doc["stopped"], sig == SIGINT ? "SIGINT" : "SIGTERM");
    ASSERT_FALSE(doc["results"].empty());
    EXPECT_LT(doc["results"].size(), 19900u);
    for (const auto& res : doc["results"]) EXPECT_TRUE(res.contains("upper"));
    std::remove(out.c_str());
  }
  std::remove(scene.c_str());
}

TEST(Cli, FitJsonHasSpecKeysAndAuditCertifies) {
  const CommandRun r = run("fit " + src("cases/models/pawn.json") + " --eps 1e-4 --json --audit");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  ASSERT_FALSE(doc["solids"].empty());
  for (const auto& s : doc["solids"]) {
    for (const char* key : {"name", "nodes", "leaves", "bytes", "build_us", "max_error", "certified_error"})
      EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_EQ(s["violations"], 0);
    EXPECT_EQ(s["unconfirmed"], 0);
    EXPECT_LE(s["certified_error"].get<double>(), s["max_error"].get<double>());
  }
}

TEST(Cli, FitWritesOneSvgPerSolid) {
  const std::string dir = testing::TempDir() + "revdist_svg_" + std::to_string(getpid());
  const CommandRun r = run("fit " + src("cases/models/paper_pairs.json") + " --eps 1e-3 --svg " + dir);
  ASSERT_EQ(r.status, 0) << r.err;
  int svgs = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) svgs += e.path().extension() == ".svg";
  EXPECT_EQ(svgs, 5);  // bottle, cup, lightmil, pawn, table
  std::filesystem::remove_all(dir);
}

}  // namespace
