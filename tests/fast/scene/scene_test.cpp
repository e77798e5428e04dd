// Scene queries (fast/scene/) against the all-pairs brute force: every pair
// within d found and none extra, brackets meeting the full distance's, the k
// closest pairs and nearest neighbours identical to sorting every pair, the
// threshold predicate agreeing with the full distance, threads changing
// nothing, and the broad phase (boxes, tree, refit) never losing a pair.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "compare/random_geometry.h"
#include "compare/scene_gen.h"
#include "core/case_io.h"
#include "core/curve_eval.h"
#include "core/input_error.h"
#include "fast/scene/aabb_tree.h"
#include "fast/scene/parallel.h"
#include "fast/scene/scene.h"
#include "../solid_test_util.h"

namespace revdist {
namespace {

using solid_test::test_seed;
using Json = nlohmann::json;
using PairKey = std::pair<std::int32_t, std::int32_t>;

Case case_from_json(const Json& doc, const std::string& name) {
  const std::string path = testing::TempDir() + "revdist_scene_test_" + name + std::to_string(getpid()) + ".json";
  std::ofstream(path) << doc.dump();
  Case c = read_case(path, false);
  std::remove(path.c_str());
  return c;
}

// Mixed solids (the shelf's) at random poses in a box: overlaps, containment,
// near and far pairs all occur.
Case random_scene(std::uint64_t seed, int n, double spread) {
  Json doc = shelf_case(4, seed);
  Json inst = Json::array();
  Rng rng(seed);
  std::vector<std::string> kinds;
  for (auto it = doc["solids"].begin(); it != doc["solids"].end(); ++it) kinds.push_back(it.key());
  for (int i = 0; i < n; ++i) {
    const Vec3 t = rng.box(spread);
    const Vec3 axis = rng.unit();
    const double angle = rng.uniform(0, M_PI);
    Json m{{"velocity", {rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), 0}},
           {"spin", {rng.uniform(-0.1, 0.1), 0, rng.uniform(-0.1, 0.1)}}};
    inst.push_back({{"name", "s" + std::to_string(i)},
                    {"solid", kinds[rng.gen()() % kinds.size()]},
                    {"rotation", {std::cos(angle / 2), std::sin(angle / 2) * axis.x(), std::sin(angle / 2) * axis.y(),
                                  std::sin(angle / 2) * axis.z()}},
                    {"translation", {t.x(), t.y(), t.z()}},
                    {"motion", m}});
  }
  doc["instances"] = inst;
  return case_from_json(doc, "random" + std::to_string(seed));
}

// Every pair's full distance (no threshold), the reference of every check.
std::map<PairKey, SolidDistanceResult> brute_force(const Scene& s) {
  std::map<PairKey, SolidDistanceResult> out;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      out[{static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)}] = solid_distance(s.solid(i), s.solid(j));
  return out;
}

double scene_scale(const Scene& s) {
  double m = 1.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    m = std::max({m, s.box(i).lo.cwiseAbs().maxCoeff(), s.box(i).hi.cwiseAbs().maxCoeff()});
  return m;
}

SceneStats expect_within_matches_brute(Scene& s, double d, const std::map<PairKey, SolidDistanceResult>& brute) {
  SceneStats st;
  const std::vector<ScenePair> found = s.within(d, &st);
  std::map<PairKey, const ScenePair*> got;
  for (const ScenePair& p : found) {
    EXPECT_LT(p.a, p.b);
    EXPECT_TRUE(got.emplace(PairKey{p.a, p.b}, &p).second) << "pair reported twice";
  }
  EXPECT_TRUE(std::is_sorted(found.begin(), found.end(),
                             [](const ScenePair& x, const ScenePair& y) { return PairKey{x.a, x.b} < PairKey{y.a, y.b}; }));
  // Both brackets hold the same distance; each side carries rounding of a few
  // hundred ulps of the world coordinates (solid_distance's own allowance).
  const double slack = 1024 * DBL_EPSILON * scene_scale(s);
  long within = 0, clear = 0;
  for (const auto& [key, full] : brute) {
    const auto it = got.find(key);
    const bool reported = it != got.end();
    if (full.upper <= d) {
      ++within;
      EXPECT_TRUE(reported) << "pair " << key.first << "," << key.second << " at " << full.upper << " <= " << d << " missed";
    }
    if (full.lower > d) {
      EXPECT_FALSE(reported) << "pair " << key.first << "," << key.second << " at " << full.lower << " > " << d;
    }
    if (!reported) continue;
    const SolidDistanceResult& r = it->second->result;
    EXPECT_LE(std::max(r.lower, full.lower), std::min(r.upper, full.upper) + slack)
        << "brackets of " << key.first << "," << key.second << " do not meet";
    EXPECT_EQ(it->second->within, r.upper <= d);
    // The predicate's answer is the full distance's whenever that one is clear.
    if (full.upper <= d || full.lower > d) {
      ++clear;
      EXPECT_EQ(it->second->within, full.upper <= d) << "threshold and full distance disagree on " << key.first << ","
                                                     << key.second;
    }
    if (full.overlap) {
      EXPECT_EQ(r.lower, 0.0);
    }
  }
  EXPECT_EQ(st.pairs_total, static_cast<long>(brute.size()));
  EXPECT_EQ(st.pairs_culled + st.pairs_tested, st.pairs_total);
  EXPECT_GT(st.pairs_culled, 0) << "the broad phase culled nothing";
  std::printf("within %.3g: %ld pairs within of %zu, %ld tested, %ld culled, %ld from the previous frame, %ld clear\n",
              d, within, brute.size(), st.pairs_tested, st.pairs_culled, st.pairs_coherent, clear);
  return st;
}

std::vector<PairKey> brute_closest(const std::map<PairKey, SolidDistanceResult>& brute, std::size_t k) {
  std::vector<std::pair<double, PairKey>> all;
  for (const auto& [key, r] : brute) all.push_back({r.upper, key});
  std::sort(all.begin(), all.end());
  std::vector<PairKey> out;
  for (std::size_t i = 0; i < std::min(k, all.size()); ++i) out.push_back(all[i].second);
  return out;
}

void expect_same(const std::vector<ScenePair>& x, const std::vector<ScenePair>& y) {
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(x[i].a, y[i].a);
    EXPECT_EQ(x[i].b, y[i].b);
    // Bit-identical: the same computation, whichever thread ran it.
    EXPECT_EQ(x[i].result.lower, y[i].result.lower);
    EXPECT_EQ(x[i].result.upper, y[i].result.upper);
    EXPECT_EQ(x[i].result.point_a, y[i].result.point_a);
    EXPECT_EQ(x[i].result.point_b, y[i].result.point_b);
    EXPECT_EQ(x[i].result.overlap, y[i].result.overlap);
    EXPECT_EQ(x[i].result.decided, y[i].result.decided);
    EXPECT_EQ(x[i].result.converged, y[i].result.converged);
    EXPECT_EQ(x[i].result.reason, y[i].result.reason);
    EXPECT_EQ(x[i].within, y[i].within);
  }
}

TEST(AabbTree, PairsWithinMatchBruteForceAfterBuildAndRefit) {
  Rng rng(test_seed(81, "AabbTree"));
  std::vector<Aabb> boxes;
  for (int i = 0; i < 400; ++i) {
    const Vec3 c = rng.box(10), h(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
    boxes.push_back({c - h, c + h});
  }
  AabbTree tree;
  tree.build(boxes);
  EXPECT_EQ(tree.size(), 2 * boxes.size() - 1);
  for (int round = 0; round < 3; ++round) {
    for (double d : {0.0, 0.3, 2.0}) {
      std::vector<PairKey> got, got3;
      tree.pairs_within(d, &got);
      tree.pairs_within(d, &got3, 3);
      EXPECT_EQ(got, got3) << "threads changed the pairs or their order";
      std::sort(got.begin(), got.end());
      std::vector<PairKey> want;
      for (int i = 0; i < 400; ++i)
        for (int j = i + 1; j < 400; ++j)
          if (boxes[i].gap(boxes[j]) <= d) want.push_back({i, j});
      EXPECT_EQ(got, want) << "round " << round << " d " << d;
    }
    // Move every box a little (refit keeps the tree) or a lot (rebuild).
    const double step = round == 0 ? 0.2 : 8.0;
    for (Aabb& b : boxes) {
      const Vec3 m = rng.box(step);
      b = {b.lo + m, b.hi + m};
    }
    tree.refit(boxes);
  }
}

// A distance that takes in more pairs than the limit stops the gathering (on
// any number of threads) and says so; at the limit exactly, every pair.
TEST(AabbTree, PairsWithinStopsPastItsLimit) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 300; ++i) boxes.push_back({Vec3(i, 0, 0), Vec3(i + 0.5, 1, 1)});
  AabbTree tree;
  tree.build(boxes);
  const std::size_t all = 300 * 299 / 2;
  for (int threads : {1, 3}) {
    std::vector<PairKey> got;
    bool over = true;
    tree.pairs_within(1e3, &got, threads, all, &over);
    EXPECT_FALSE(over);
    EXPECT_EQ(got.size(), all);
    got.clear();
    tree.pairs_within(1e3, &got, threads, all - 1, &over);
    EXPECT_TRUE(over) << threads << " threads";
    EXPECT_LE(got.size(), 2 * all);
  }
}

TEST(Scene, BoxesHoldTheSolids) {
  const Case c = random_scene(test_seed(5, "BoxesHoldTheSolids"), 30, 3.0);
  Scene s(c, SceneOptions{});
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> U(0, 1);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const PosedSolid& p = s.solid(i);
    for (const Piece& piece : p.profile->pieces)
      for (int k = 0; k <= 20; ++k) {
        const auto [u0, u1] = piece_domain(piece);
        const Vec2 q = piece_point(piece, u0 + k / 20.0 * (u1 - u0));
        const double phi = 2 * M_PI * U(g);
        const Vec3 x = p.R * Vec3(q.x() * std::cos(phi), q.x() * std::sin(phi), q.y()) + p.t;
        EXPECT_TRUE((x.array() >= s.box(i).lo.array()).all() && (x.array() <= s.box(i).hi.array()).all())
            << "instance " << i << " point outside its box";
      }
  }
}

TEST(Scene, WithinMatchesBruteForceOnMixedSolids) {
  const Case c = random_scene(test_seed(11, "WithinMixed"), 36, 2.5);
  SceneOptions plain;
  plain.coherence = false;
  Scene s(c, plain);
  const auto brute = brute_force(s);
  for (double d : {0.0, 0.05, 0.4}) expect_within_matches_brute(s, d, brute);
  // Moving mixed solids with coherence: settled pairs keep the brute force's answers.
  Scene m(c, SceneOptions{});
  for (double f : {0.0, 1.0}) {
    SceneStats st;
    m.set_frame(f, &st);
    expect_within_matches_brute(m, 0.3, brute_force(m));
  }
}

TEST(Scene, WithinMatchesBruteForceOnMovingRingMesh) {
  const Case c = case_from_json(ring_mesh_case(21, test_seed(3, "RingMesh")), "rings");
  Scene s(c, SceneOptions{});
  long coherent = 0;
  // Frame 1 settles pairs from frame 0 (coherence), frame 9 is a jump.
  for (double f : {0.0, 1.0, 9.0}) {
    SceneStats st;
    s.set_frame(f, &st);
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Pose p = pose_at_frame(c.instances[i].pose, c.instances[i].motion, f);
      EXPECT_EQ(s.solid(i).t, p.translation);
      EXPECT_EQ(s.solid(i).R, p.rotation());
    }
    const auto brute = brute_force(s);
    coherent += expect_within_matches_brute(s, 0.2, brute).pairs_coherent;
  }
  EXPECT_GT(coherent, 0) << "no pair was settled from its previous frame";
}

// Keyframed solids whose time runs ("time_rate"): a grid of the bundled
// `morph` solid, each at its own time, deforming and spinning over frames.
Case deforming_scene(std::uint64_t seed, int side) {
  std::ifstream in(solid_test::source_path("cases/models/morph.json"));
  const Json morph = Json::parse(in);
  Json doc{{"format", "revdist/1"}, {"solids", {{"morph", morph["solids"]["morph"]}}}};
  Rng rng(seed);
  Json inst = Json::array();
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      inst.push_back({{"name", "m" + std::to_string(i) + "_" + std::to_string(j)},
                      {"solid", "morph"},
                      {"time", rng.uniform(0, 4)},
                      {"translation", {1.3 * i, 1.3 * j, rng.uniform(-0.1, 0.1)}},
                      {"motion", {{"time_rate", rng.uniform(-0.3, 0.3)}, {"spin", {0, 0, rng.uniform(-0.05, 0.05)}}}}});
  doc["instances"] = inst;
  return case_from_json(doc, "deforming" + std::to_string(seed));
}

TEST(Scene, DeformingShapesMatchBruteForceLazyOrEager) {
  const Case c = deforming_scene(test_seed(29, "Deforming"), 3);
  SceneOptions lazy, threads;
  lazy.lazy_trees = true;
  threads.lazy_trees = true;
  threads.threads = 2;  // shapes rebuilt in parallel too
  Scene e(c, SceneOptions{}), l(c, lazy), t2(c, threads);
  long lazy_built = 0, eager_built = 0;
  for (double f : {0.0, 1.0, 7.0}) {
    SceneStats se, sl, st2;
    e.set_frame(f, &se);
    l.set_frame(f, &sl);
    t2.set_frame(f, &st2);
    for (std::size_t i = 0; i < e.size(); ++i) {
      const double t = time_at_frame(c.instances[i].time, c.instances[i].motion, f, 4.0);
      EXPECT_GE(t, 0.0);
      EXPECT_LE(t, 4.0);
      // The blend at the frame's time, in both scenes.
      const Profile want = profile_at(c.solids[0], t);
      for (const Scene* sc : {&e, &l, &t2})
        for (std::size_t k = 0; k < want.pieces.size(); ++k)
          EXPECT_EQ(sc->solid(i).profile->pieces[k].points, want.pieces[k].points) << "instance " << i << " frame " << f;
    }
    const auto brute = brute_force(e);
    expect_within_matches_brute(e, 0.3, brute);
    const std::vector<ScenePair> pe = e.within(0.3, &se), pl = l.within(0.3, &sl);
    // Both ask the same queries of trees with the same numbers.
    expect_same(pe, pl);
    expect_same(pl, t2.within(0.3, &st2));
    EXPECT_EQ(sl.nodes_built, st2.nodes_built);
    EXPECT_GT(pe.size(), 0u) << "no pair within 0.3: the test would check nothing";
    lazy_built += sl.nodes_built;
    eager_built += se.nodes_built;
  }
  std::printf("deforming scene: nodes built over 3 frames, eager %ld, lazy %ld\n", eager_built, lazy_built);
  EXPECT_LT(lazy_built, eager_built);
}

// A shape's tree is built when a query first needs it. Instances of one
// keyframed solid, each at a time of its own and standing still, are as many
// shapes: the closest pair builds the trees of the pairs it asks about, not
// all 100 (hostile-input review: 100000 of them took 32 s and 2.9 GB to
// answer with 22 narrow-phase calls, all trees built at the start). Until a
// tree is built its boxes come from the control points' hull, and must hold
// the solid; the answers are the brute force's.
TEST(Scene, TreesAreBuiltOnlyForTheShapesQueriesTouch) {
  std::ifstream in(solid_test::source_path("cases/models/morph.json"));
  const Json morph = Json::parse(in);
  Json doc{{"format", "revdist/1"}, {"solids", {{"morph", morph["solids"]["morph"]}}}};
  Rng rng(test_seed(31, "TreesBuiltOnDemand"));
  Json inst = Json::array();
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      inst.push_back({{"name", "m" + std::to_string(i) + "_" + std::to_string(j)},
                      {"solid", "morph"},
                      {"time", rng.uniform(0, 4)},
                      {"translation", {2.4 * i, 2.4 * j, rng.uniform(-0.1, 0.1)}}});
  doc["instances"] = inst;
  const Case c = case_from_json(doc, "distinct_shapes");
  long all_nodes = 0;
  {
    const CaseModel eager = build_case_model(c, SceneOptions{}.eps);
    ASSERT_EQ(eager.shapes.size(), 100u);
    for (const auto& shape : eager.shapes) all_nodes += static_cast<long>(shape->tree.nodes.size());
  }
  Scene s(c, SceneOptions{});
  // The hull boxes hold the solids (sampled, before any tree is built).
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> U(0, 1);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Profile want = profile_at(c.solids[0], c.instances[i].time);
    for (const Piece& piece : want.pieces)
      for (int k = 0; k <= 40; ++k) {
        const auto [u0, u1] = piece_domain(piece);
        const Vec2 q = piece_point(piece, u0 + k / 40.0 * (u1 - u0));
        const double phi = 2 * M_PI * U(g);
        const Vec3 x = Vec3(q.x() * std::cos(phi), q.x() * std::sin(phi), q.y()) + c.instances[i].pose.translation;
        EXPECT_TRUE((x.array() >= s.box(i).lo.array()).all() && (x.array() <= s.box(i).hi.array()).all())
            << "instance " << i << " point outside its box";
      }
  }
  SceneStats st;
  s.set_frame(0.0, &st);  // reports what the scene built before any question (nothing)
  const std::vector<ScenePair> got = s.closest(1, &st);
  std::printf("100 distinct shapes: frame 0 and the closest pair built %ld of %ld nodes, %ld narrow calls\n", st.nodes_built, all_nodes,
              st.narrow_calls);
  EXPECT_LT(st.nodes_built, all_nodes / 10);
  const auto brute = brute_force(s);  // builds every tree
  const std::vector<PairKey> want = brute_closest(brute, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(PairKey(got[0].a, got[0].b), want[0]);
  // Neighbours on the grid, not all pairs: the boxes cull.
  const double d = got[0].result.upper + 0.3;
  const long near = std::count_if(brute.begin(), brute.end(), [&](const auto& kv) { return kv.second.upper <= d; });
  EXPECT_GT(near, 0);
  const SceneStats w = expect_within_matches_brute(s, d, brute);
  EXPECT_GT(w.pairs_culled, 4950 / 2);
}

TEST(Scene, TimeRunsBackAndForthThroughTheKeyframes) {
  InstanceMotion m;
  m.time_rate = 0.7;
  double prev = time_at_frame(3.5, m, 0, 4.0);
  EXPECT_EQ(prev, 3.5);
  for (int f = 1; f < 200; ++f) {
    const double t = time_at_frame(3.5, m, f, 4.0);
    EXPECT_GE(t, 0.0);
    EXPECT_LE(t, 4.0);
    EXPECT_LE(std::abs(t - prev), 0.7 + 1e-12) << "frame " << f;  // continuous: at most one step per frame
    prev = t;
  }
  EXPECT_NEAR(time_at_frame(3.5, m, 1, 4.0), 4.0 - 0.2, 1e-12);  // reflected at the last keyframe
  EXPECT_THROW(read_case_text(R"({"format": "revdist/1", "solids": {"ball": {"profile": [{"arc": [[0, -1], [1, 0], [0, 1]]}]}},
      "instances": [{"name": "a", "solid": "ball", "motion": {"time_rate": 0.1}}]})", "static.json"), InputError);
}

TEST(Scene, ClosestAndNearestMatchSortingEveryPair) {
  const Case c = random_scene(test_seed(17, "Closest"), 30, 3.0);
  Scene s(c, SceneOptions{});
  const auto brute = brute_force(s);
  for (std::size_t k : {1, 4, 40}) {
    SceneStats st;
    const std::vector<ScenePair> got = s.closest(k, &st);
    const std::vector<PairKey> want = brute_closest(brute, k);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(PairKey(got[i].a, got[i].b), want[i]) << "k " << k << " rank " << i;
      // Reported brackets are plain full distances.
      EXPECT_EQ(got[i].result.lower, brute.at(want[i]).lower);
      EXPECT_EQ(got[i].result.upper, brute.at(want[i]).upper);
    }
    EXPECT_EQ(st.pairs_culled + st.pairs_tested, st.pairs_total);
  }
  for (std::int32_t q : {0, 13}) {
    SceneStats st;
    const std::vector<ScenePair> got = s.nearest(q, 3, &st);
    std::vector<std::pair<double, std::int32_t>> all;
    for (std::int32_t j = 0; j < static_cast<std::int32_t>(s.size()); ++j)
      if (j != q) all.push_back({brute.at({std::min(q, j), std::max(q, j)}).upper, j});
    std::sort(all.begin(), all.end());
    ASSERT_EQ(got.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(got[i].a, q);
      EXPECT_EQ(got[i].b, all[i].second) << "nearest of " << q << " rank " << i;
    }
  }
}

// within(d, ..., max_answers): more pairs certainly within d (points of
// both surfaces that close) than max_answers refuse the frame before any
// narrow-phase call; fewer answer as without the cap.
TEST(Scene, WithinRefusesBeforeQueryingWhenCertainPairsExceedTheCap) {
  const Case c = random_scene(test_seed(29, "WithinCap"), 40, 3.0);
  Scene capped(c, {}), plain(c, {});
  SceneStats a, b;
  capped.set_frame(0.0, &a);
  plain.set_frame(0.0, &b);
  const std::vector<ScenePair> all = plain.within(1e6, &b);  // every pair: all surface points are that close
  ASSERT_GT(all.size(), 10u);
  std::vector<ScenePair> out(3);
  SceneStats st;
  EXPECT_FALSE(capped.within(1e6, &st, &out, all.size() - 1));
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(st.narrow_calls, 0);
  EXPECT_TRUE(capped.within(1e6, &st, &out, all.size()));
  expect_same(all, out);
}

TEST(Scene, ThreadsGiveBitIdenticalAnswers) {
  const Case c = random_scene(test_seed(23, "Threads"), 40, 3.0);
  SceneOptions one, three;
  three.threads = 3;
  Scene s1(c, one), s3(c, three);
  std::vector<ScenePair> reused;  // s3 answers into the same vector every frame (its elements reused)
  for (double f : {0.0, 1.0, 2.0, 4.0}) {
    SceneStats a, b;
    s1.set_frame(f, &a);
    s3.set_frame(f, &b);
    s3.within(0.3, &b, &reused);
    expect_same(s1.within(0.3, &a), reused);
    EXPECT_EQ(a.pairs_coherent, b.pairs_coherent);
    expect_same(s1.closest(5, &a), s3.closest(5, &b));
    expect_same(s1.nearest(2, 4, &a), s3.nearest(2, 4, &b));
    EXPECT_EQ(a.pairs_tested, b.pairs_tested);
    EXPECT_EQ(a.pairs_threshold, b.pairs_threshold);
    EXPECT_EQ(a.narrow_calls, b.narrow_calls);
    EXPECT_EQ(a.node_pairs, b.node_pairs);
  }
}

// The worker pool: every index exactly once, for any thread count, call
// after call (the workers persist), with a caller's nested call and with two
// callers at once (one of which finds the pool busy and uses threads of its own).
TEST(ParallelFor, ThreadsRunEveryIndexOnce) {
  for (int threads : {1, 2, 3, 8}) {
    for (std::size_t n : {0u, 1u, 5u, 1000u}) {
      std::vector<int> hits(n, 0);
      parallel_for(n, threads, [&](std::size_t i) { ++hits[i]; });
      EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), static_cast<long>(n)) << threads << " threads, n " << n;
    }
  }
  std::vector<long> sums(2, 0);
  std::thread other([&] {
    for (int r = 0; r < 20; ++r) {
      std::vector<long> part(64, 0);
      parallel_for(64, 2, [&](std::size_t i) { part[i] = static_cast<long>(i); });
      for (long v : part) sums[1] += v;
    }
  });
  for (int r = 0; r < 20; ++r) {
    std::vector<long> inner(16, 0);
    parallel_for_workers(16, 3, [&](std::size_t i, std::size_t w) {
      EXPECT_LT(w, 3u);
      std::vector<int> nested(10, 0);
      parallel_for(10, 2, [&](std::size_t j) { nested[j] = 1; });
      inner[i] = std::count(nested.begin(), nested.end(), 1);
    });
    for (long v : inner) sums[0] += v;
  }
  other.join();
  EXPECT_EQ(sums[0], 20 * 16 * 10);
  EXPECT_EQ(sums[1], 20 * (63 * 64 / 2));
}

TEST(ParallelFor, ThreadsRethrowTheFirstFailure) {
  for (int r = 0; r < 3; ++r) {  // the pool still works after a failed job
    EXPECT_THROW(parallel_for(100, 2, [](std::size_t i) {
                   if (i == 57) throw std::runtime_error("index 57");
                 }),
                 std::runtime_error);
    std::vector<int> hits(100, 0);
    parallel_for(100, 2, [&](std::size_t i) { hits[i] = 1; });
    EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), 100);
  }
}

}  // namespace
}  // namespace revdist
