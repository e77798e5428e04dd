// Thread safety of the fast query (fast/solid_distance.h: "any number of queries
// may share [profiles and trees] across threads"): the same queries from several
// threads at once, over shared trees, must give the single-threaded answers bit
// for bit. Also built under -fsanitize=thread by scripts/sanitize.sh thread.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist {
namespace {

namespace fs = std::filesystem;

struct Query {
  const PosedSolid* a;
  const PosedSolid* b;
  DistanceOptions o;
};

bool same(const SolidDistanceResult& x, const SolidDistanceResult& y) {
  return x.lower == y.lower && x.upper == y.upper && x.distance == y.distance && x.overlap == y.overlap &&
         x.converged == y.converged && x.decided == y.decided && x.reason == y.reason && x.point_a == y.point_a &&
         x.point_b == y.point_b && x.stats.node_pairs == y.stats.node_pairs &&
         x.stats.patch_pairs == y.stats.patch_pairs && x.stats.refined == y.stats.refined;
}

TEST(SolidDistanceThreads, ConcurrentQueriesAreBitIdentical) {
  std::vector<std::string> files;
  for (const char* dir : {"cases/models", "cases/distance"})
    for (const auto& e : fs::directory_iterator(std::string(REVDIST_SOURCE_DIR) + "/" + dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<Case> cases;
  std::vector<CaseModel> models;
  for (const std::string& f : files) {
    cases.push_back(read_case(f));
    models.push_back(build_case_model(cases.back(), 1e-5));
  }
  // Every query at two tolerances and as a threshold predicate: the refinement
  // below the leaves (tight tol) and the early exits are exercised too.
  std::vector<Query> queries;
  for (std::size_t f = 0; f < cases.size(); ++f) {
    const CaseModel& m = models[f];
    for (const auto& [ia, ib] : cases[f].queries) {
      DistanceOptions o;
      o.tol = 1e-6;
      queries.push_back({&m.instances[ia], &m.instances[ib], o});
      o.tol = 1e-10;
      queries.push_back({&m.instances[ia], &m.instances[ib], o});
      o.tol = 1e-6;
      o.threshold = 0.05;
      queries.push_back({&m.instances[ia], &m.instances[ib], o});
    }
  }
  ASSERT_GT(queries.size(), 90u);
  std::vector<SolidDistanceResult> serial;
  for (const Query& q : queries) serial.push_back(solid_distance(*q.a, *q.b, q.o));

  const int kThreads = 4;
  std::vector<std::vector<SolidDistanceResult>> got(kThreads, std::vector<SolidDistanceResult>(queries.size()));
  std::vector<std::thread> pool;
  for (int t = 0; t < kThreads; ++t)
    pool.emplace_back([&, t] {
      // Each thread starts elsewhere in the list, so different queries overlap in time.
      for (std::size_t k = 0; k < queries.size(); ++k) {
        const std::size_t i = (k + t * queries.size() / kThreads) % queries.size();
        got[t][i] = solid_distance(*queries[i].a, *queries[i].b, queries[i].o);
      }
    });
  for (std::thread& th : pool) th.join();
  int differ = 0;
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t i = 0; i < queries.size(); ++i)
      if (!same(got[t][i], serial[i])) {
        ++differ;
        ADD_FAILURE() << "thread " << t << " query " << i << ": [" << got[t][i].lower << ", " << got[t][i].upper
                      << "] vs serial [" << serial[i].lower << ", " << serial[i].upper << "]";
      }
  std::printf("[ threads  ] %d threads x %zu queries, %d differ from the serial run\n", kThreads, queries.size(),
              differ);
}

}  // namespace
}  // namespace revdist
