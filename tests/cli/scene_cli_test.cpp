// End-to-end checks of `revdist scene` and `revdist scene-gen`: the JSON keys
// of SPEC section 5, frames and threads, and exit status 2 with one line on bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace {

using revdist_test::CommandRun;
using revdist_test::run;

std::string generated(const std::string& kind, int n) {
  const std::string path = testing::TempDir() + "revdist_scene_cli_" + kind + std::to_string(getpid()) + ".json";
  const CommandRun g = run("scene-gen " + kind + " --n " + std::to_string(n) + " --seed 4 --out " + path);
  EXPECT_EQ(g.status, 0) << g.err;
  return path;
}

TEST(SceneCli, WithinJsonHasSpecKeysAndFrames) {
  const std::string path = generated("rings", 40);
  const CommandRun r = run("scene " + path + " --within 0.3 --frames 3 --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "revdist-scene/1");
  ASSERT_TRUE(j["pairs"].is_array());
  ASSERT_FALSE(j["pairs"].empty());
  for (const auto& p : j["pairs"]) {
    for (const char* k : {"a", "b", "lower", "upper", "overlap", "within"}) EXPECT_TRUE(p.contains(k)) << k;
    EXPECT_LE(p["lower"].get<double>(), 0.3);
    EXPECT_LE(p["lower"].get<double>(), p["upper"].get<double>());
  }
  for (const char* k : {"pairs_tested", "pairs_culled", "nodes_built", "time_ms"}) EXPECT_TRUE(j["stats"].contains(k)) << k;
  EXPECT_GT(j["stats"]["pairs_culled"].get<long>(), 0);
  EXPECT_GT(j["stats"]["nodes_built"].get<long>(), 0);
  ASSERT_EQ(j["frames"].size(), 3u);
  // Trees are cached per shape: later frames build none.
  EXPECT_EQ(j["frames"][2]["stats"]["nodes_built"].get<long>(), 0);
  std::remove(path.c_str());
}

TEST(SceneCli, ClosestAndNearestOnAShelf) {
  const std::string path = generated("shelf", 30);
  const CommandRun c = run("scene " + path + " --closest 3 --json");
  ASSERT_EQ(c.status, 0) << c.err;
  const nlohmann::json j = nlohmann::json::parse(c.out);
  ASSERT_EQ(j["pairs"].size(), 3u);
  EXPECT_LE(j["pairs"][0]["upper"].get<double>(), j["pairs"][2]["upper"].get<double>());
  const CommandRun n = run("scene " + path + " --nearest board0 --closest 2");
  EXPECT_EQ(n.status, 0) << n.err;
  EXPECT_NE(n.out.find("board0"), std::string::npos);
  std::remove(path.c_str());
}

TEST(SceneCli, BadInputExitsTwoWithOneLine) {
  const std::string path = generated("rings", 20);
  for (const char* args : {"--within -1", "--within 0.1 --closest 2", "--nearest nobody", "--threads 0",
                                  "--frames 0", "--eps 0"}) {
    const CommandRun r = run("scene " + path + " " + std::string(args));
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  const CommandRun missing = run("scene /nonexistent/scene.json");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("/nonexistent/scene.json"), std::string::npos);
  EXPECT_EQ(run("scene-gen cubes").status, 2);
  // (--n 10^7, once allowed, ran out of memory and aborted.)
  const CommandRun big = run("scene-gen rings --n 100001 --out " + path);
  EXPECT_EQ(big.status, 2) << big.err;
  EXPECT_NE(big.err.find("100000"), std::string::npos) << big.err;
  // Every frame's pairs stay in memory until the one document is written:
  // past 500000 records, refused before anything is written (60 spheres
  // --within 100 for 100000 frames aborted out of memory).
  {
    std::string t = R"({"format": "revdist/1", "solids": {"s": {"profile": [{"arc": [[0, -1], [1, 0], [0, 1]]}]}}, "instances": [)";
    for (int i = 0; i < 60; ++i)
      t += (i ? ", " : "") + std::string(R"({"name": "s)") + std::to_string(i) + R"(", "solid": "s", "translation": [)" +
           std::to_string(3 * (i % 8)) + ", " + std::to_string(3 * (i / 8)) + ", 0]}";
    const std::string many = testing::TempDir() + "revdist_scene_records_" + std::to_string(getpid()) + ".json";
    std::ofstream(many) << t << "]}";
    const CommandRun r = run("scene " + many + " --within 100 --frames 300 --json");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_NE(r.err.find("more than 500000 pair records"), std::string::npos) << r.err;
    std::remove(many.c_str());
  }
  // (--closest 10^9 ran out of memory.)
  EXPECT_EQ(run("scene " + path + " --closest 1000000000").status, 2);
  std::remove(path.c_str());
}

}  // namespace
