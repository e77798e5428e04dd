// Scene benchmarks (issue 8): the ring mesh of the paper's Figure 1 in motion.
//  - BM_SceneWithin/N/T: one frame (poses, boxes, broad-phase refit, all pairs
//    within d = 0.3) of an N-ring mesh on T threads; counters give the median
//    and p90 per frame of the wall time and of the CPU time summed over the
//    threads (per-thread clocks), and the pairs found and tested.
//  - BM_SceneScaling/N: 1 against 2 threads on the same frames, interleaved
//    (scaling of throughput, CPU ratio, serial share; see below).
//  - BM_Threshold/d: every broad-phase candidate pair of a 1000-ring mesh,
//    once as the predicate "closer than d?" and once as a full distance
//    (tol 1e-6); counters: per-pair CPU medians of both and their ratio, over
//    the pairs whose answer is clear (the full bracket is at least 10% of d away from d).
//  - BM_DeformableFrame/lazy/predicate/apart: the keyframed `morph` solid
//    (cases/models) at a new time every frame, blended, its tree rebuilt
//    (eager, or lazy: down to the spiral level) and queried against a static
//    copy on a near-contact motion (gap 1 % of the size, or 10 % when apart;
//    full distance at tol 2 eps, or the predicate "closer than 2 % of the
//    size?"); counters: per-frame CPU
//    medians/p90 of blend + rebuild + query, of the query alone, of blend +
//    rebuild, of the whole profile's spiral split, and the nodes built (tree + query).
//  - BM_SceneDeforming/lazy: frames of a 20 x 20 grid of deforming `morph`
//    instances (time_rate), all pairs within 0.1, eager or lazy trees.
// REVDIST_SEED overrides the motion seed.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/motion.h"
#include "compare/random_geometry.h"
#include "compare/scene_gen.h"
#include "core/case_io.h"
#include "fast/scene/parallel.h"
#include "fast/scene/scene.h"
#include "fast/spiral_split.h"

namespace {

using namespace revdist;

std::uint64_t seed() {
  const char* s = std::getenv("REVDIST_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 8u;
}

Case ring_case(int rings) {
  const std::string path = "/tmp/revdist_bench_scene_" + std::to_string(rings) + ".json";
  std::FILE* f = std::fopen(path.c_str(), "w");
  const std::string text = ring_mesh_case(rings, seed()).dump();
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  Case c = read_case(path, false);
  std::remove(path.c_str());
  return c;
}

double quantile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

void BM_SceneWithin(benchmark::State& state) {
  const Case c = ring_case(static_cast<int>(state.range(0)));
  SceneOptions o;
  o.threads = static_cast<int>(state.range(1));
  Scene scene(c, o);
  std::vector<double> wall, cpu;
  long frame = 0, found = 0, tested = 0;
  for (auto _ : state) {
    SceneStats st;
    scene.set_frame(static_cast<double>(frame++ % 24), &st);
    const std::vector<ScenePair> pairs = scene.within(0.3, &st);
    benchmark::DoNotOptimize(pairs.data());
    wall.push_back(st.time_ms);
    cpu.push_back(st.cpu_ms);
    found += static_cast<long>(pairs.size());
    tested += st.pairs_tested;
  }
  state.counters["instances"] = static_cast<double>(scene.size());
  state.counters["wall_ms_median"] = quantile(wall, 0.5);
  state.counters["wall_ms_p90"] = quantile(wall, 0.9);
  state.counters["cpu_ms_median"] = quantile(cpu, 0.5);
  state.counters["cpu_ms_p90"] = quantile(cpu, 0.9);
  state.counters["pairs_within"] = static_cast<double>(found) / static_cast<double>(frame);
  state.counters["pairs_tested"] = static_cast<double>(tested) / static_cast<double>(frame);
}

double load_average() {
  double load = -1.0;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = -1.0;
    std::fclose(f);
  }
  return load;
}

//  BM_SceneScaling/N: throughput of 1 against 2 threads on the same frames,
//  interleaved (frame f on the 1-thread scene, then on the 2-thread one) so
//  that the load of a shared machine falls on both alike: the ratio of summed
//  wall times is the scaling; the ratio of summed CPU (all threads) shows
//  contention (1 if none); the serial share bounds what 2 cores can give
//  (Amdahl). Frames 1..24 of the motion, repeated; frame 0 (every pair
//  computed from scratch) is left out. The answers must agree pair by pair.
void BM_SceneScaling(benchmark::State& state) {
  const Case c = ring_case(static_cast<int>(state.range(0)));
  SceneOptions o1, o2;
  o2.threads = 2;
  Scene s1(c, o1), s2(c, o2);
  std::vector<double> wall[2], cpu[2], serial[2], span[2];
  std::vector<ScenePair> pairs[2];
  long frame = 0, differ = 0;
  const double load0 = load_average();
  for (auto _ : state) {
    const double f = static_cast<double>(frame++ % 25);
    for (int k = 0; k < 2; ++k) {
      Scene& s = k ? s2 : s1;
      SceneStats st;
      s.set_frame(f, &st);
      s.within(0.3, &st, &pairs[k]);
      if (f == 0) continue;
      wall[k].push_back(st.time_ms);
      cpu[k].push_back(st.cpu_ms);
      serial[k].push_back(st.serial_ms);
      span[k].push_back(st.span_ms);
    }
    differ += pairs[0].size() != pairs[1].size();
    for (std::size_t i = 0; i < std::min(pairs[0].size(), pairs[1].size()); ++i)
      differ += pairs[0][i].a != pairs[1][i].a || pairs[0][i].b != pairs[1][i].b ||
                pairs[0][i].result.lower != pairs[1][i].result.lower || pairs[0][i].result.upper != pairs[1][i].result.upper;
  }
  auto sum = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); };
  state.counters["load_before"] = load0;
  state.counters["load_after"] = load_average();
  state.counters["frames"] = static_cast<double>(wall[0].size());
  state.counters["differing_answers"] = static_cast<double>(differ);
  for (int k = 0; k < 2; ++k) {
    const std::string t = k ? "_2t" : "_1t";
    state.counters["wall_ms_median" + t] = quantile(wall[k], 0.5);
    state.counters["wall_ms_p90" + t] = quantile(wall[k], 0.9);
    state.counters["cpu_ms_median" + t] = quantile(cpu[k], 0.5);
    state.counters["cpu_ms_p90" + t] = quantile(cpu[k], 0.9);
    state.counters["serial_ms_median" + t] = quantile(serial[k], 0.5);
  }
  state.counters["scaling"] = sum(wall[0]) / sum(wall[1]);
  // Per-thread CPU: 1 thread's CPU over the 2-thread frames' span (serial part
  // plus each step's busiest worker), the scaling on two free cores, wake-ups aside.
  state.counters["span_ms_median_2t"] = quantile(span[1], 0.5);
  state.counters["span_scaling"] = sum(cpu[0]) / sum(span[1]);
  state.counters["cpu_ratio"] = sum(cpu[1]) / sum(cpu[0]);
  const double share = sum(serial[1]) / sum(cpu[1]);
  state.counters["serial_share_2t"] = share;
  state.counters["amdahl_bound"] = sum(cpu[0]) / (sum(serial[1]) + (sum(cpu[1]) - sum(serial[1])) / 2);
}

void BM_Threshold(benchmark::State& state) {
  const double d = static_cast<double>(state.range(0)) / 100.0;
  const Case c = ring_case(1000);
  Scene scene(c, SceneOptions{});
  SceneStats st;
  scene.set_frame(5.0, &st);
  std::vector<std::pair<std::int32_t, std::int32_t>> cand;
  scene.broad_phase().pairs_within(d, &cand);
  std::sort(cand.begin(), cand.end());
  std::vector<double> t_thr, t_full, ratio;
  long clear = 0, agree = 0;
  for (auto _ : state) {
    t_thr.clear();
    t_full.clear();
    ratio.clear();
    clear = agree = 0;
    for (const auto& [a, b] : cand) {
      DistanceOptions full, thr;
      thr.threshold = d;
      double t0 = thread_cpu_seconds();
      const SolidDistanceResult rt = solid_distance(scene.solid(a), scene.solid(b), thr);
      const double tt = thread_cpu_seconds() - t0;
      t0 = thread_cpu_seconds();
      const SolidDistanceResult rf = solid_distance(scene.solid(a), scene.solid(b), full);
      const double tf = thread_cpu_seconds() - t0;
      if (!(rf.lower > 1.1 * d || rf.upper < 0.9 * d)) continue;
      ++clear;
      agree += (rt.upper <= d) == (rf.upper <= d);
      t_thr.push_back(1e6 * tt);
      t_full.push_back(1e6 * tf);
      ratio.push_back(tf / std::max(tt, 1e-9));
    }
  }
  state.counters["pairs_clear"] = static_cast<double>(clear);
  state.counters["agree"] = static_cast<double>(agree);
  state.counters["threshold_us_median"] = quantile(t_thr, 0.5);
  state.counters["threshold_us_p90"] = quantile(t_thr, 0.9);
  state.counters["full_us_median"] = quantile(t_full, 0.5);
  state.counters["full_us_p90"] = quantile(t_full, 0.9);
  state.counters["speedup_median"] = quantile(ratio, 0.5);
  state.counters["speedup_p10"] = quantile(ratio, 0.1);
}

// The paper's Figure 8 setting: a static copy of `morph` (time 0) and the
// deformable one on a near-contact motion (compare/motion.h, gap about 1 % of
// the size), the deformable solid at a new time every frame.
struct DeformableMotion {
  SolidDef def;
  Profile fixed_profile;
  BiarcTree fixed_tree;
  std::vector<double> times;
  std::vector<MotionFrame> frames;
  double size = 0.0;
  DeformableMotion(int n, double clearance) {
    const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/models/morph.json");
    def = c.solids[0];
    fixed_profile = profile_at(def, 0.0);
    fixed_tree = build_biarc_tree(fixed_profile, 1e-5);
    size = profile_extent(fixed_profile);
    // Times spread over every keyframe interval; eager trees for planning the motion only.
    std::vector<Profile> profiles(n);
    std::vector<BiarcTree> trees(n);
    for (int j = 0; j < n; ++j) {
      times.push_back(static_cast<double>(def.keyframes.size() - 1) * (j + 0.5) / n);
      profiles[j] = profile_at(def, times[j]);
      trees[j] = build_biarc_tree(profiles[j], 1e-5);
    }
    MotionOptions mo;
    mo.frames = n;
    mo.clearance = clearance;
    mo.seed = seed();
    const PosedSolid a{&fixed_profile, &fixed_tree, Mat3::Identity(), Vec3::Zero()};
    frames = near_contact_motion(a, [&](int j) { return PosedSolid{&profiles[j], &trees[j], Mat3::Identity(), Vec3::Zero()}; }, mo);
  }
};

void BM_DeformableFrame(benchmark::State& state) {
  const bool lazy = state.range(0) != 0;
  const bool predicate = state.range(1) != 0;
  static const DeformableMotion near(200, 1e-2), apart(200, 1e-1);
  const DeformableMotion& m = state.range(2) ? apart : near;
  const PosedSolid base{&m.fixed_profile, &m.fixed_tree, Mat3::Identity(), Vec3::Zero()};
  DistanceOptions o;
  o.tol = 2e-5;  // the paper's: twice eps
  if (predicate) o.threshold = 2e-2 * m.size;  // "closer than 2 % of the size?"
  Profile profile;
  BiarcTree tree;
  std::vector<double> frame_us, query_us, nodes, split_us;
  std::vector<SpiralSpan> spirals;  // the spiral split alone, timed apart (outside the frame)
  std::size_t j = 0;
  for (auto _ : state) {
    const MotionFrame& f = m.frames[j];
    const double time = m.times[j];
    j = (j + 1) % m.frames.size();
    const double t0 = thread_cpu_seconds();
    profile = profile_at(m.def, time);
    rebuild_biarc_tree(profile, 1e-5, tree, nullptr, lazy);
    const double t1 = thread_cpu_seconds();
    PosedSolid a = base;
    a.R = f.R_WA, a.t = f.t_WA;
    const PosedSolid b{&profile, &tree, f.R_WB, f.t_WB};
    const SolidDistanceResult r = solid_distance(a, b, o);
    const double t2 = thread_cpu_seconds();
    benchmark::DoNotOptimize(r.upper);
    frame_us.push_back(1e6 * (t2 - t0));
    query_us.push_back(1e6 * (t2 - t1));
    nodes.push_back(static_cast<double>(tree.nodes.size() + r.stats.nodes_built));
    const double t3 = thread_cpu_seconds();
    split_into_spirals(profile, spirals);
    split_us.push_back(1e6 * (thread_cpu_seconds() - t3));
  }
  state.counters["frame_us_median"] = quantile(frame_us, 0.5);
  state.counters["frame_us_p90"] = quantile(frame_us, 0.9);
  state.counters["query_us_median"] = quantile(query_us, 0.5);
  // Blend + build: what laziness can save; the spiral split of the whole
  // profile is part of it either way (the tree's top is made of the spirals).
  std::vector<double> build_us(frame_us.size());
  for (std::size_t i = 0; i < frame_us.size(); ++i) build_us[i] = frame_us[i] - query_us[i];
  state.counters["build_us_median"] = quantile(build_us, 0.5);
  state.counters["spiral_split_us_median"] = quantile(split_us, 0.5);
  state.counters["nodes_built_median"] = quantile(nodes, 0.5);
}

// A grid of side x side `morph` instances, each at its own keyframe time
// running at its own rate (README "Scenes": time_rate) and spinning.
Case deforming_grid(int side) {
  std::ifstream in(std::string(REVDIST_SOURCE_DIR) + "/cases/models/morph.json");
  const nlohmann::json morph = nlohmann::json::parse(in);
  nlohmann::json doc{{"format", "revdist/1"}, {"solids", {{"morph", morph["solids"]["morph"]}}}};
  Rng rng(seed());
  nlohmann::json inst = nlohmann::json::array();
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      inst.push_back({{"name", "m" + std::to_string(i) + "_" + std::to_string(j)},
                      {"solid", "morph"},
                      {"time", rng.uniform(0, 4)},
                      {"translation", {1.4 * i, 1.4 * j, 0}},
                      {"motion", {{"time_rate", rng.uniform(-0.1, 0.1)}, {"spin", {0, 0, rng.uniform(-0.02, 0.02)}}}}});
  doc["instances"] = inst;
  return read_case_text(doc.dump(), "deforming_grid.json");
}

//  BM_SceneDeforming/lazy: frames of a 20 x 20 deforming grid (every shape
//  blended and rebuilt each frame), all pairs within 0.1; per-frame CPU.
void BM_SceneDeforming(benchmark::State& state) {
  const Case c = deforming_grid(20);
  SceneOptions o;
  o.lazy_trees = state.range(0) != 0;
  Scene scene(c, o);
  std::vector<double> cpu, built;
  long frame = 1, found = 0;
  for (auto _ : state) {
    SceneStats st;
    scene.set_frame(static_cast<double>(frame++), &st);
    const std::vector<ScenePair> pairs = scene.within(0.1, &st);
    benchmark::DoNotOptimize(pairs.data());
    cpu.push_back(st.cpu_ms);
    built.push_back(static_cast<double>(st.nodes_built));
    found += static_cast<long>(pairs.size());
  }
  state.counters["cpu_ms_median"] = quantile(cpu, 0.5);
  state.counters["cpu_ms_p90"] = quantile(cpu, 0.9);
  state.counters["nodes_built_median"] = quantile(built, 0.5);
  state.counters["pairs_within"] = static_cast<double>(found) / static_cast<double>(frame - 1);
}

}  // namespace

BENCHMARK(BM_SceneDeforming)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(30);
BENCHMARK(BM_DeformableFrame)->ArgsProduct({{0, 1}, {0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond)->Iterations(2000);
BENCHMARK(BM_SceneWithin)->Args({1000, 1})->Args({1000, 2})->Args({10000, 1})->Args({10000, 2})
    ->Unit(benchmark::kMillisecond)->Iterations(8);
BENCHMARK(BM_SceneScaling)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(100);
BENCHMARK(BM_Threshold)->Arg(10)->Arg(20)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond)->Iterations(1);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("build_type", REVDIST_BUILD_TYPE);
  benchmark::AddCustomContext("build_flags", REVDIST_BUILD_FLAGS);
  benchmark::AddCustomContext("seed", std::to_string(seed()));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
