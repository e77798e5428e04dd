// Lazy biarc trees (fast/biarc_tree.h, issue 8): expanded completely they are
// the eager tree, and every query through them gives the eager tree's answer
// bit for bit (bundled cases, seeded random poses, threshold predicates, several
// threads over shared lazy trees) while building only the nodes it reaches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/case_io.h"
#include "fast/biarc_tree.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"
#include "solid_test_util.h"

namespace revdist {
namespace {

namespace fs = std::filesystem;
using namespace solid_test;

constexpr double kEps = 1e-5;

std::vector<std::string> bundled_files() {
  std::vector<std::string> files;
  for (const char* dir : {"cases/models", "cases/distance"})
    for (const auto& e : fs::directory_iterator(std::string(REVDIST_SOURCE_DIR) + "/" + dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// Everything a caller sees, bit for bit, except the count of nodes built.
void expect_same(const SolidDistanceResult& x, const SolidDistanceResult& y, const std::string& what) {
  EXPECT_TRUE(x.lower == y.lower && x.upper == y.upper && x.distance == y.distance && x.overlap == y.overlap &&
              x.converged == y.converged && x.decided == y.decided && x.reason == y.reason &&
              x.point_a == y.point_a && x.point_b == y.point_b && x.stats.node_pairs == y.stats.node_pairs &&
              x.stats.bounds == y.stats.bounds && x.stats.leaf_pairs == y.stats.leaf_pairs &&
              x.stats.patch_pairs == y.stats.patch_pairs && x.stats.refined == y.stats.refined)
      << what << ": lazy [" << y.lower << ", " << y.upper << "] node_pairs " << y.stats.node_pairs << " vs eager ["
      << x.lower << ", " << x.upper << "] node_pairs " << x.stats.node_pairs;
}

// The nodes below `node` in depth-first order (left child first), through a view.
void collect(BiarcTreeView& v, std::int32_t node, std::vector<BiarcNode>* nodes, std::vector<BiarcFit>* fits) {
  const BiarcNode n = v.node(node);
  nodes->push_back(n);
  if (n.fit >= 0) fits->push_back(v.fit(n.fit));
  if (n.leaf()) return;
  const std::int32_t c = v.children(node);
  collect(v, c, nodes, fits);
  collect(v, c + 1, nodes, fits);
}

TEST(LazyTree, ExpandedCompletelyItIsTheEagerTree) {
  int profiles = 0;
  for (const std::string& f : bundled_files()) {
    const Case c = read_case(f);
    for (const SolidDef& s : c.solids) {
      const Profile& p = s.keyframes.back();
      const BiarcTree eager = build_biarc_tree(p, kEps);
      BuildStats st;
      const BiarcTree lazy = build_biarc_tree(p, kEps, &st, true);
      EXPECT_LE(lazy.nodes.size(), eager.nodes.size());
      for (const BiarcNode& n : lazy.nodes) EXPECT_FALSE(n.pending() && n.fit < 0) << "pending above the spiral level";
      BiarcTreeView ve(eager, p), vl(lazy, p);
      std::vector<BiarcNode> ne, nl;
      std::vector<BiarcFit> fe, fl;
      collect(ve, 0, &ne, &fe);
      collect(vl, 0, &nl, &fl);
      EXPECT_EQ(ve.nodes_built(), 0);
      EXPECT_EQ(static_cast<std::size_t>(vl.nodes_built()) + lazy.nodes.size(), eager.nodes.size()) << f << " " << s.name;
      ASSERT_EQ(ne.size(), nl.size()) << f << " " << s.name;
      ASSERT_EQ(fe.size(), fl.size()) << f << " " << s.name;
      for (std::size_t i = 0; i < ne.size(); ++i) {
        EXPECT_TRUE(ne[i].seg_a == nl[i].seg_a && ne[i].seg_b == nl[i].seg_b && ne[i].radius == nl[i].radius &&
                    ne[i].leaf() == nl[i].leaf())
            << f << " " << s.name << " node " << i;
      }
      for (std::size_t i = 0; i < fe.size(); ++i) {
        EXPECT_TRUE(fe[i].eps == fl[i].eps && fe[i].u0 == fl[i].u0 && fe[i].u1 == fl[i].u1 &&
                    fe[i].arcs == fl[i].arcs && fe[i].depth == fl[i].depth &&
                    fe[i].arc[0].start == fl[i].arc[0].start && fe[i].arc[0].curvature == fl[i].arc[0].curvature &&
                    fe[i].arc[0].length == fl[i].arc[0].length && fe[i].arc[1].length == fl[i].arc[1].length)
            << f << " " << s.name << " fit " << i;
      }
      ++profiles;
    }
  }
  EXPECT_GT(profiles, 10);
}

TEST(LazyTree, BundledQueriesGiveTheEagerBrackets) {
  long built = 0, eager_nodes = 0, queries = 0;
  for (const std::string& f : bundled_files()) {
    const Case c = read_case(f);
    const CaseModel eager = build_case_model(c, kEps), lazy = build_case_model(c, kEps, true);
    for (const auto& [ia, ib] : c.queries) {
      // Default and tight tol (refinement below the leaves) and a threshold predicate.
      DistanceOptions o[3];
      o[1].tol = 1e-10;
      o[2].threshold = 0.05;
      for (const DistanceOptions& opt : o) {
        const SolidDistanceResult x = solid_distance(eager.instances[ia], eager.instances[ib], opt);
        const SolidDistanceResult y = solid_distance(lazy.instances[ia], lazy.instances[ib], opt);
        expect_same(x, y, fs::path(f).stem().string() + " " + c.instances[ia].name + "-" + c.instances[ib].name);
        EXPECT_EQ(x.stats.nodes_built, 0);
        built += y.stats.nodes_built;
        eager_nodes += static_cast<long>(eager.instances[ia].tree->nodes.size() + eager.instances[ib].tree->nodes.size());
        ++queries;
      }
    }
  }
  std::printf("[ lazy     ] %ld queries built %ld nodes; eager trees of the same pairs hold %ld\n", queries, built,
              eager_nodes);
  EXPECT_GT(queries, 90);
  EXPECT_LT(built, eager_nodes / 2) << "lazy queries should build a fraction of the trees";
}

TEST(LazyTree, RandomPosesGiveTheEagerBrackets) {
  std::mt19937_64 g(test_seed(8101, "RandomPosesGiveTheEagerBrackets"));
  const Case c = read_case(source_path("cases/models/paper_pairs.json"));
  const CaseModel eager = build_case_model(c, kEps), lazy = build_case_model(c, kEps, true);
  std::normal_distribution<double> N(0, 1);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 40; ++k) {
    const std::size_t ia = g() % c.instances.size(), ib = g() % c.instances.size();
    const Mat3 Ra = rotation_of(random_quaternion(g)), Rb = rotation_of(random_quaternion(g));
    const Vec3 ta(N(g), N(g), N(g)), tb = ta + Vec3(N(g), N(g), N(g)).normalized() * 2.5 * U(g);
    DistanceOptions o;
    if (k % 3 == 1) o.tol = 1e-9;
    if (k % 3 == 2) o.threshold = 0.5 * U(g);
    PosedSolid ea = eager.instances[ia], eb = eager.instances[ib], la = lazy.instances[ia], lb = lazy.instances[ib];
    ea.R = la.R = Ra;
    eb.R = lb.R = Rb;
    ea.t = la.t = ta;
    eb.t = lb.t = tb;
    expect_same(solid_distance(ea, eb, o), solid_distance(la, lb, o), "trial " + std::to_string(k));
  }
}

// Views are per query: many threads over the same lazy trees give the serial answers.
TEST(LazyTree, ConcurrentQueriesOverSharedLazyTrees) {
  std::vector<Case> cases;
  for (const std::string& f : bundled_files()) cases.push_back(read_case(f));
  std::vector<CaseModel> models;
  for (const Case& c : cases) models.push_back(build_case_model(c, kEps, true));
  // Serial answers on one set of lazy trees, the threads' on a fresh set.
  std::vector<CaseModel> fresh;
  for (const Case& c : cases) fresh.push_back(build_case_model(c, kEps, true));
  std::vector<std::pair<const PosedSolid*, const PosedSolid*>> queries;
  std::vector<SolidDistanceResult> serial;
  for (std::size_t f = 0; f < cases.size(); ++f)
    for (const auto& [ia, ib] : cases[f].queries) {
      queries.push_back({&fresh[f].instances[ia], &fresh[f].instances[ib]});
      serial.push_back(solid_distance(models[f].instances[ia], models[f].instances[ib]));
    }
  const int kThreads = 4;
  std::vector<std::vector<SolidDistanceResult>> got(kThreads, std::vector<SolidDistanceResult>(queries.size()));
  std::vector<std::thread> pool;
  for (int t = 0; t < kThreads; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t k = 0; k < queries.size(); ++k) {
        const std::size_t i = (k + t * queries.size() / kThreads) % queries.size();
        got[t][i] = solid_distance(*queries[i].first, *queries[i].second);
      }
    });
  for (std::thread& th : pool) th.join();
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t i = 0; i < queries.size(); ++i) expect_same(serial[i], got[t][i], "thread " + std::to_string(t));
}

}  // namespace
}  // namespace revdist
