// Benchmarks of biarc tree construction (paper section 4.1, Figure 9 and
// Tables 1-2): rebuild time per model at eps = 1e-3, 1e-4, 1e-5 (the hot path
// of deformable solids; target <= 0.5 ms at 1e-5), with counters for nodes,
// leaves, bytes, the proven max error and the node growth per decade of eps
// (cubic convergence predicts 10^(1/3) = 2.15). One more benchmark rebuilds the
// deformable `morph` solid at a new time per iteration (blend + rebuild).
// Models: cases/models/*.json (REVDIST_MODELS_DIR overrides the directory).
// Build flags are printed in the context.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/case_io.h"
#include "fast/biarc_tree.h"

namespace {

using namespace revdist;

std::string models_dir() {
  const char* d = std::getenv("REVDIST_MODELS_DIR");
  return d ? d : std::string(REVDIST_SOURCE_DIR) + "/cases/models";
}

struct Model {
  std::string name;
  SolidDef solid;
};

std::vector<Model> load_models() {
  std::vector<Model> out;
  for (const char* name : {"pawn", "cup", "bottle", "table", "lightmil", "morph"}) {
    try {
      const Case c = read_case(models_dir() + "/" + name + ".json");
      for (const SolidDef& s : c.solids) out.push_back({name, s});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_fit: skipping %s: %s\n", name, e.what());
    }
  }
  return out;
}

void bm_build(benchmark::State& state, const Profile& profile, double eps) {
  BiarcTree tree;
  BuildStats st;
  rebuild_biarc_tree(profile, eps, tree, &st);  // warm-up: storage reaches its size
  BuildStats coarser;
  build_biarc_tree(profile, eps * 10, &coarser);
  for (auto _ : state) {
    rebuild_biarc_tree(profile, eps, tree);
    benchmark::DoNotOptimize(tree.nodes.data());
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = st.nodes;
  state.counters["leaves"] = st.leaves;
  state.counters["spirals"] = st.spirals;
  state.counters["bytes"] = static_cast<double>(st.bytes);
  state.counters["max_error"] = st.max_error;
  state.counters["leaves_per_decade"] = static_cast<double>(st.leaves) / coarser.leaves;
  state.counters["unproven"] = st.unproven;
}

// Deformable: blend the keyframes at a new time and rebuild, every iteration.
void bm_deform(benchmark::State& state, const SolidDef& solid, double eps) {
  BiarcTree tree;
  const double span = static_cast<double>(solid.keyframes.size() - 1);
  int i = 0;
  BuildStats st;
  double max_nodes = 0;
  for (auto _ : state) {
    const double time = span * ((i++ * 37) % 1000) / 999.0;
    const Profile p = profile_at(solid, time);
    rebuild_biarc_tree(p, eps, tree, &st);
    max_nodes = std::max(max_nodes, static_cast<double>(st.nodes));
    benchmark::DoNotOptimize(tree.nodes.data());
  }
  state.counters["max_nodes"] = max_nodes;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("build_type", REVDIST_BUILD_TYPE);
  benchmark::AddCustomContext("build_flags", REVDIST_BUILD_FLAGS);
  static const std::vector<Model> models = load_models();
  for (const Model& m : models) {
    const Profile* profile = new Profile(profile_at(m.solid, 0.0));  // lives for the run
    for (double eps : {1e-3, 1e-4, 1e-5}) {
      char name[128];
      std::snprintf(name, sizeof name, "build/%s/eps:%.0e", m.name.c_str(), eps);
      benchmark::RegisterBenchmark(name, [profile, eps](benchmark::State& s) { bm_build(s, *profile, eps); })
          ->Unit(benchmark::kMicrosecond);
    }
    if (m.solid.deformable()) {
      for (double eps : {1e-3, 1e-5}) {
        char name[128];
        std::snprintf(name, sizeof name, "deform/%s/eps:%.0e", m.name.c_str(), eps);
        const SolidDef* solid = &m.solid;
        benchmark::RegisterBenchmark(name, [solid, eps](benchmark::State& s) { bm_deform(s, *solid, eps); })
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
