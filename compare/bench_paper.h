// The paper's section 5 experiments against an FCL 0.7 OBBRSS mesh baseline
// (`revdist bench`): Tables 1-2 (tree sizes), Figure 9 (build and deformable
// rebuild time), Figure 8 (queries against the deformable model), Figure 12
// (pairs in continuous near-contact motion), at equal accuracy checked against
// the certified engine on a sample of frames. Timings are per-thread CPU time
// (CLOCK_THREAD_CPUTIME_ID) per call, summarised by medians and p90.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "compare/motion.h"
#include "core/profile.h"

namespace revdist {

// The most frames per pair a run takes (--frames): about half an hour.
constexpr int kMaxBenchFrames = 20000;

struct BenchOptions {
  std::vector<double> eps = {1e-3, 1e-4, 1e-5};
  int frames = 200;         // frames per pair (Figure 12) and of the deformable model (Figures 8, 9)
  int exact_frames = 2;     // frames per pair checked by the certified engine (0: none)
  // Certified engine budget per frame (uncertified frames are counted, not
  // used). 20,000 left 4 of the 30 motion frames and 1 of the 10 deforming
  // ones uncertified at --frames 2000; 2,000,000 (compare's) certifies all 40
  // in the same 68 s of CPU for the whole run without FCL.
  long exact_max_boxes = 2000000;
  double proven_tol = 1e-6;      // the proven mode timed beside tol = 2 eps
  // The eps of the "sweep" experiment: revdist alone at tol = 2 eps on every
  // Figure 12 frame, for the growth of query time with eps (FCL meshes of
  // 1e-7 chordal error would not fit in memory). Empty: every decade from
  // the largest eps down to 1/100 of the smallest (1e-3 ... 1e-7 by default),
  // none below what check_bench allows.
  std::vector<double> sweep_eps;
  std::uint64_t seed = 20200501;
  bool fcl = true;
  // The motion frames' file (`--poses`): read when it exists (it must be one
  // this option wrote for the same source, seed, frames and pairs), else the
  // frames are placed as usual and written there. The frames are placed by
  // root-finding on the fast engine's distances, so two builds place slightly
  // different poses; with one file both time the same ones. Empty: no file.
  std::string poses_file;
  // Called with one line of progress at a time (no newline).
  std::function<void(const std::string&)> progress;
};

// What is benchmarked: static solids (every pair i <= j moves near contact) and
// deformable ones (each plays Mt against every static solid).
struct BenchInput {
  std::string source;  // "paper" or the case file
  struct Solid {
    std::string name;
    SolidDef def;
  };
  std::vector<Solid> statics, deformables;
};

// The paper's five models (cases/models/paper_pairs.json) and Mt
// (cases/models/morph.json), from models_dir.
BenchInput paper_bench_input(const std::string& models_dir);
// The solids of a revdist/1 case (InputError on bad input).
BenchInput case_bench_input(const std::string& case_file);
// Where `paper` finds its models: $REVDIST_MODELS_DIR, else the source tree's cases/models.
std::string default_models_dir();

// One record per (experiment, pair, eps). Times in microseconds of thread CPU
// time; NaN where a column does not apply (no FCL side for Figure 8).
struct BenchRecord {
  // "build" (Tables 1-2, Figure 9), "deform" (Figure 8), "motion" (Figure 12),
  // "sweep" (revdist alone on Figure 12's frames over BenchOptions::sweep_eps).
  std::string experiment;
  std::string pair;        // "a-b"; the model's name for "build"; "all" for "sweep"
  double eps = 0.0;
  double tol = 0.0;        // revdist tolerance of the timed queries (2 eps)
  int samples = 0;         // timed calls per side
  double median_us = 0.0, p90_us = 0.0, mean_us = 0.0;
  double fcl_median_us = 0.0, fcl_p90_us = 0.0, fcl_mean_us = 0.0;
  double ratio = 0.0;      // FCL median / revdist median, same run
  double proven_median_us = 0.0, proven_p90_us = 0.0;  // tol = proven_tol ("motion")
  // The same frames at tol = 2 eps in sequence, each query warm-started from
  // the previous frame's answer (WarmStart, frame coherence; "motion").
  double coherent_median_us = NAN, coherent_p90_us = NAN, coherent_overlap_p99_us = NAN;
  long nodes = 0, leaves = 0;   // revdist tree nodes (sum over the pair)
  long bytes = 0;
  long fcl_triangles = 0, fcl_bv_nodes = 0, fcl_bytes = 0;
  // Work counters, means per revdist query.
  double node_pairs = 0, leaf_pairs = 0, patch_pairs = 0, quick_pairs = 0, local_pairs = 0, refined = 0;
  int overlaps = 0;        // frames revdist proved overlapping
  // Frames planned to overlap slightly (negative gap target). Not all of them
  // overlap: the motion solves the gap along one approach and pushes in along
  // it, which may leave the solids apart where the approach grazes.
  int planned_overlaps = 0;
  // Frames that do overlap, by a reference query (tol 1e-9 x size, finest
  // trees): a proven overlap, or a bracket [0, <= tol] (touching, counted
  // with them). revdist's time on them: the issue's "overlap proven in
  // <= 50 us for 99 % of slightly overlapping poses".
  int overlapping_frames = 0;
  double overlap_median_us = 0.0, overlap_p99_us = 0.0;
  // revdist's p99 on the frames it proved overlapping (`overlaps` of them).
  double proven_overlap_p99_us = NAN;
  int unconverged = 0;     // revdist queries that did not reach tol
  int fcl_zero = 0;        // frames FCL reported 0 (intersecting triangles)
  // revdist's p99 on the frames FCL reported 0: overlapping poses chosen by
  // the other engine (planned overlaps include frames the motion left apart).
  double fcl_zero_p99_us = NAN;
  // Accuracy on the certified sample: |answer - certified distance| (max), and
  // brackets that miss the certified interval (must be 0).
  int exact_frames = 0, exact_uncertified = 0;
  double max_err = 0, proven_max_err = 0, fcl_max_err = 0;
  int violations = 0;
};

struct BenchResult {
  BenchOptions options;
  std::string source;
  std::vector<BenchRecord> records;
  double cpu_s = 0.0;  // thread CPU time of the whole run
};

// The motion frames of a run as `poses_file` keeps them, pair by pair in the
// run's order (the Figure 12 pairs, then the deformable ones).
struct BenchPoses {
  std::string source;
  std::uint64_t seed = 0;
  int frames = 0;
  std::vector<std::pair<std::string, std::vector<MotionFrame>>> pairs;
};
// Binary: a magic line "revdist-bench-poses/1", the header, then each pair's
// name and frames (rotations, translations, target, achieved gap, setup
// evaluations); doubles bit for bit.
std::string encode_bench_poses(const BenchPoses& poses);
// The inverse; an InputError naming `file` and the problem for anything that
// is not such a file (wrong magic, truncated, trailing bytes, a count or name
// out of range, a value not finite, a rotation not orthonormal to 1e-9).
BenchPoses decode_bench_poses(const std::string& bytes, const std::string& file);

// Refuses, with an InputError and before any work, what the run could not do:
// no eps, frames < 1, an eps below what doubles resolve for a solid (1e-12 of
// its extent), or an FCL mesh beyond kMaxMeshTriangles (compare/mesh_fcl.h).
void check_bench(const BenchInput& input, const BenchOptions& options);
BenchResult run_bench(const BenchInput& input, const BenchOptions& options);

}  // namespace revdist
