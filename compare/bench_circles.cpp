// Benchmarks of the circle-circle kernel (fast/circle_distance): time per random
// pair for the distance (the leaf kernel of the distance query) and for the
// binormal enumeration. Pairs are generated outside the timed loop from a fixed
// seed (REVDIST_SEED overrides it); counters report ns per pair.
// Build flags: see CMakeLists.txt (Release, -ffp-contract=off); printed in the context.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "fast/circle_distance.h"

namespace {

using revdist::Circle3;
using revdist::Vec3;

std::uint64_t bench_seed() {
  const char* s = std::getenv("REVDIST_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 20261121u;
}

// Random pairs as in the "random" family: centres in [-1,1]^3, uniform normals, radii in [0.05, 1].
std::vector<std::pair<Circle3, Circle3>> random_pairs(int n, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> box(-1, 1), rad(0.05, 1);
  std::normal_distribution<double> g;
  auto unit = [&] {
    Vec3 v;
    do v = Vec3(g(gen), g(gen), g(gen)); while (v.squaredNorm() < 1e-12);
    return Vec3(v.normalized());
  };
  std::vector<std::pair<Circle3, Circle3>> v;
  v.reserve(n);
  for (int i = 0; i < n; ++i) {
    Circle3 a{Vec3(box(gen), box(gen), box(gen)), unit(), rad(gen)};
    Circle3 b{Vec3(box(gen), box(gen), box(gen)), unit(), rad(gen)};
    v.emplace_back(a, b);
  }
  return v;
}

void BM_CircleDistanceRandom(benchmark::State& state) {
  const auto pairs = random_pairs(4096, bench_seed());
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& p = pairs[i++ & 4095];
    auto r = revdist::circle3_circle3_distance(p.first, p.second);
    benchmark::DoNotOptimize(r);
  }
  state.counters["time_per_pair"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CircleDistanceRandom);

// Near-contact pairs (b passes within 1e-9 of a point of a): the slow path.
void BM_CircleDistanceNearContact(benchmark::State& state) {
  std::mt19937_64 gen(bench_seed() + 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::pair<Circle3, Circle3>> pairs;
  for (int i = 0; i < 1024; ++i) {
    const double ra = 0.1 + 0.9 * u(gen), rb = 0.1 + 0.9 * u(gen), phi = 6.283 * u(gen);
    const Vec3 p(ra * std::cos(phi), ra * std::sin(phi), 1e-9);
    const Vec3 nb = Vec3(u(gen) - 0.5, u(gen) - 0.5, u(gen) - 0.5).normalized();
    const Vec3 dir = nb.cross(Vec3(0.3, 0.5, 0.7)).normalized();
    pairs.push_back({Circle3{Vec3::Zero(), Vec3::UnitZ(), ra}, Circle3{p + rb * dir, nb, rb}});
  }
  std::size_t i = 0;
  for (auto _ : state) {
    auto r = revdist::circle3_circle3_distance(pairs[i & 1023].first, pairs[i & 1023].second);
    ++i;
    benchmark::DoNotOptimize(r);
  }
  state.counters["time_per_pair"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CircleDistanceNearContact);

void BM_CircleBinormalsRandom(benchmark::State& state) {
  const auto pairs = random_pairs(1024, bench_seed());
  std::size_t i = 0, lines = 0;
  for (auto _ : state) {
    const auto& p = pairs[i++ & 1023];
    auto r = revdist::circle3_circle3_binormals(p.first, p.second);
    lines += r.size();
    benchmark::DoNotOptimize(r);
  }
  state.counters["time_per_pair"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["binormals_per_pair"] = static_cast<double>(lines) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_CircleBinormalsRandom);

}  // namespace

int main(int argc, char** argv) {
  benchmark::AddCustomContext("build_flags", "Release -O3 -ffp-contract=off (CMAKE_BUILD_TYPE=Release)");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
