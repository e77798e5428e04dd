// Benchmarks of the solid distance query (paper section 4.2, Alg. 2; Table 3
// and Figure 10 of the paper): per pair of the paper's models
// (cases/models/paper_pairs.json queries), 32 random poses at random
// separations 0.01-1 x size (log-uniform), query time at eps in {1e-3, 1e-4,
// 1e-5}, tol = 1e-6. Per-query times are measured individually so the
// counters give the median and p90 (the target is a median <= 20 us at 1e-5);
// node_pairs, leaf_pairs, patch_pairs and refined are means per query.
// Same-run baseline: FCL 0.7 mesh-mesh distance (OBBRSS) on meshes sampled
// from the profile at chordal error eps (REVDIST_BENCH_FCL_EPS, default 1e-3,1e-4);
// ratio = FCL median / revdist median at the same eps and poses.
// REVDIST_SEED overrides the pose seed. Build flags are printed in the context.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/case_io.h"
#include "core/curve_eval.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"
#include "compare/mesh_fcl.h"
#include "compare/thread_clock.h"

namespace {

using namespace revdist;
using Clock = std::chrono::steady_clock;

constexpr double kTol = 1e-6;
constexpr int kPoses = 32;

std::uint64_t seed() {
  const char* s = std::getenv("REVDIST_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 20200501u;
}

struct PosePair {
  Mat3 Ra, Rb;
  Vec3 ta, tb;
  double target;
};

Mat3 random_rotation(std::mt19937_64& g) {
  std::normal_distribution<double> N(0, 1);
  Pose p;
  for (double& c : p.q) c = N(g);
  return p.rotation();
}

double profile_size(const Profile& p) {
  double s = 0;
  for (const Piece& piece : p.pieces)
    for (const Vec2& q : piece.points) s = std::max({s, q.x(), std::abs(q.y())});
  return s;
}

// Random poses with b at a target separation along a random direction: the
// translation is corrected by the measured distance a few times (setup only).
std::vector<PosePair> make_poses(const PosedSolid& a, const PosedSolid& b, std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  const double size = std::max(profile_size(*a.profile), profile_size(*b.profile));
  std::vector<PosePair> out;
  while (static_cast<int>(out.size()) < kPoses) {
    PosePair p{random_rotation(g), random_rotation(g), Vec3::Zero(), Vec3::Zero(), 0};
    p.target = size * std::pow(10.0, -2.0 + 2.0 * U(g));
    const Vec3 dir = Vec3(N(g), N(g), N(g)).normalized();
    PosedSolid A = a, B = b;
    A.R = p.Ra;
    B.R = p.Rb;
    B.t = 3 * size * dir;
    bool ok = false;
    for (int it = 0; it < 6; ++it) {
      const SolidDistanceResult r = solid_distance(A, B, DistanceOptions{kTol});
      if (r.overlap || !std::isfinite(r.distance)) break;
      if (std::abs(r.distance - p.target) < 2e-2 * p.target) {
        ok = true;
        break;
      }
      B.t += (p.target - r.distance) * dir;
    }
    if (!ok) continue;
    p.ta = A.t;
    p.tb = B.t;
    out.push_back(p);
  }
  return out;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))];
}

struct PairData {
  std::string name;
  std::size_t ia, ib;
  std::vector<PosePair> poses;
};

// One benchmark iteration = one query, cycling through the poses.
void bm_distance(benchmark::State& state, const CaseModel* m, const std::vector<const PairData*> pairs) {
  std::vector<double> times, cpu;
  double node_pairs = 0, leaf_pairs = 0, patch_pairs = 0, refined = 0, converged = 0, n = 0;
  std::size_t i = 0;
  const std::size_t total = pairs.size() * kPoses;
  for (auto _ : state) {
    const PairData& pd = *pairs[(i / kPoses) % pairs.size()];
    const PosePair& p = pd.poses[i % kPoses];
    ++i;
    PosedSolid A = m->instances[pd.ia], B = m->instances[pd.ib];
    A.R = p.Ra, A.t = p.ta, B.R = p.Rb, B.t = p.tb;
    const double c0 = thread_cpu_us();
    const auto t0 = Clock::now();
    const SolidDistanceResult r = solid_distance(A, B, DistanceOptions{kTol});
    const auto t1 = Clock::now();
    cpu.push_back(thread_cpu_us() - c0);
    benchmark::DoNotOptimize(r.lower);
    times.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    node_pairs += r.stats.node_pairs, leaf_pairs += r.stats.leaf_pairs, patch_pairs += r.stats.patch_pairs;
    refined += r.stats.refined, converged += r.converged, n += 1;
  }
  (void)total;
  state.counters["median_us"] = percentile(times, 0.5);
  state.counters["p90_us"] = percentile(times, 0.9);
  state.counters["median_cpu_us"] = percentile(cpu, 0.5);
  state.counters["node_pairs"] = node_pairs / n;
  state.counters["leaf_pairs"] = leaf_pairs / n;
  state.counters["patch_pairs"] = patch_pairs / n;
  state.counters["refined"] = refined / n;
  state.counters["converged"] = converged / n;
}

void bm_fcl(benchmark::State& state, std::shared_ptr<const FclMesh> ma, std::shared_ptr<const FclMesh> mb, long tris,
            const std::vector<PosePair>* poses, const CaseModel* m, std::size_t ia, std::size_t ib, double eps) {
  std::vector<double> times, cpu;
  double max_err = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const PosePair& p = (*poses)[i++ % poses->size()];
    const auto t0 = Clock::now();
    const FclDistanceResult f = fcl_mesh_distance(*ma, p.Ra, p.ta, *mb, p.Rb, p.tb);
    const auto t1 = Clock::now();
    cpu.push_back(f.cpu_us);
    const double ret = f.distance;
    benchmark::DoNotOptimize(ret);
    times.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    if (i <= poses->size()) {
      PosedSolid A = m->instances[ia], B = m->instances[ib];
      A.R = p.Ra, A.t = p.ta, B.R = p.Rb, B.t = p.tb;
      const double d = solid_distance(A, B, DistanceOptions{kTol}).distance;
      if (std::getenv("REVDIST_BENCH_DEBUG")) std::fprintf(stderr, "fcl %.9g revdist %.9g\n", ret, d);
      max_err = std::max(max_err, std::abs(ret - d));
    }
  }
  state.counters["fcl_median_us"] = percentile(times, 0.5);
  state.counters["fcl_p90_us"] = percentile(times, 0.9);
  state.counters["fcl_median_cpu_us"] = percentile(cpu, 0.5);
  state.counters["triangles"] = static_cast<double>(tris);
  state.counters["max_abs_err_vs_revdist"] = max_err;
  state.counters["eps"] = eps;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("build_type", REVDIST_BUILD_TYPE);
  benchmark::AddCustomContext("build_flags", REVDIST_BUILD_FLAGS);
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/models/paper_pairs.json");
  std::mt19937_64 g(seed());
  static std::map<double, std::unique_ptr<CaseModel>> models;
  static std::vector<std::unique_ptr<PairData>> pairs;
  for (double eps : {1e-3, 1e-4, 1e-5}) models[eps] = std::make_unique<CaseModel>(build_case_model(c, eps));
  // Poses are made once (at 1e-5) and shared by every eps and by FCL.
  for (const auto& [ia, ib] : c.queries) {
    auto pd = std::make_unique<PairData>();
    pd->name = c.instances[ia].name + "-" + c.instances[ib].name;
    pd->ia = ia, pd->ib = ib;
    pd->poses = make_poses(models[1e-5]->instances[ia], models[1e-5]->instances[ib], g);
    pairs.push_back(std::move(pd));
  }
  for (auto& [eps, m] : models) {
    std::vector<const PairData*> all;
    for (const auto& pd : pairs) all.push_back(pd.get());
    char name[160];
    std::snprintf(name, sizeof name, "distance/all/eps:%.0e", eps);
    CaseModel* mp = m.get();
    benchmark::RegisterBenchmark(name, [mp, all](benchmark::State& s) { bm_distance(s, mp, all); })
        ->Unit(benchmark::kMicrosecond);
    if (eps == 1e-5) {
      for (const PairData* pd : all) {
        std::snprintf(name, sizeof name, "distance/%s/eps:%.0e", pd->name.c_str(), eps);
        benchmark::RegisterBenchmark(name, [mp, pd](benchmark::State& s) { bm_distance(s, mp, {pd}); })
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
  std::vector<double> fcl_eps = {1e-3, 1e-4};
  if (const char* e = std::getenv("REVDIST_BENCH_FCL_EPS")) {
    fcl_eps.clear();
    for (std::string s = e; !s.empty();) {
      const std::size_t k = s.find(',');
      fcl_eps.push_back(std::stod(s.substr(0, k)));
      s = k == std::string::npos ? "" : s.substr(k + 1);
    }
  }
  for (double eps : fcl_eps) {
    std::map<std::string, std::pair<std::shared_ptr<const FclMesh>, long>> meshes;
    for (std::size_t i = 0; i < c.instances.size(); ++i) {
      const std::string& solid = c.solids[c.instances[i].solid].name;
      if (!meshes.count(solid)) {
        auto mesh = make_fcl_mesh(mesh_solid(*models[1e-5]->instances[i].profile, eps));
        meshes[solid] = {mesh, fcl_mesh_triangles(*mesh)};
      }
    }
    for (const auto& pd : pairs) {
      const auto& [ma, ta] = meshes[c.solids[c.instances[pd->ia].solid].name];
      const auto& [mb, tb] = meshes[c.solids[c.instances[pd->ib].solid].name];
      char name[160];
      std::snprintf(name, sizeof name, "fcl/%s/eps:%.0e", pd->name.c_str(), eps);
      const PairData* p = pd.get();
      CaseModel* m = models[1e-5].get();
      benchmark::RegisterBenchmark(name, [=](benchmark::State& s) {
        bm_fcl(s, ma, mb, ta + tb, &p->poses, m, p->ia, p->ib, eps);
      })->Unit(benchmark::kMicrosecond);
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
