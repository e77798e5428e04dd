// Scene queries over many posed solids (issue 8): all pairs closer than d, the
// k closest pairs, the nearest neighbours of one instance, the minimum over the
// scene. A broad phase over world boxes (fast/scene/aabb_tree.h) ensures far
// pairs are never touched; the narrow phase is solid_distance
// (fast/solid_distance.h), as a threshold predicate where the question allows.
// Answers do not depend on the number of threads.
#pragma once
#include <cstdint>
#include <limits>
#include <vector>

#include "core/profile.h"
#include "fast/case_model.h"
#include "fast/scene/aabb_tree.h"
#include "fast/solid_distance.h"

namespace revdist {

struct SceneOptions {
  double eps = 1e-5;          // biarc bound of every shape's tree
  DistanceOptions distance;   // tol, rel_tol, budgets (threshold is the queries' own)
  int threads = 1;
  // Frame coherence of within(d) at the scene level (the narrow phase is not
  // touched): a pair's last bracket and witness points are kept with the
  // pair's relative pose; on a later frame the witness points at the new poses
  // give an upper bound and the old lower bound minus the most any point can
  // have moved relative to the other solid a lower bound, which settles the
  // pair without a narrow-phase call when either decides "within d?".
  bool coherence = true;
  // Lazy biarc trees (fast/biarc_tree.h) for the shapes whose keyframe time
  // changes every frame ("time_rate"): a frame then costs what the queries
  // touch. Static shapes stay eager: built once and shared by many pairs, they
  // would be expanded again by every query (lazy expansion is per query).
  bool lazy_trees = false;
};

inline constexpr std::size_t kMaxWithinPairs = 2000000;

struct ScenePair {
  std::int32_t a = 0, b = 0;  // instance indices, a < b (nearest: a is the query instance)
  SolidDistanceResult result;
  // within(d): upper <= d proven. A pair whose bracket met tol while still
  // straddling d is reported with within = false (it is not proven farther).
  bool within = false;
};

struct SceneStats {
  long instances = 0;
  long pairs_total = 0;      // n (n - 1) / 2
  long pairs_tested = 0;     // pairs the narrow phase touched
  long pairs_culled = 0;     // never touched (pairs_total - pairs_tested)
  long pairs_threshold = 0;  // settled by the threshold predicate before the bracket met tol
  long pairs_coherent = 0;   // settled from the pair's previous frame, without a narrow-phase call
  long narrow_calls = 0;     // solid_distance calls (k closest reruns a pair that enters the top k)
  long node_pairs = 0;       // narrow-phase work, summed
  long nodes_built = 0;      // biarc tree nodes built for this frame: shapes (cached per shape; deforming
                             // ones rebuilt) and, with lazy trees, the nodes the queries expanded
  long broad_nodes = 0;      // nodes of the broad-phase tree
  bool broad_rebuilt = false;  // the broad phase was rebuilt rather than refitted this frame
  double time_ms = 0.0;      // wall time of the frame (poses, boxes, broad and narrow phase)
  double cpu_ms = 0.0;       // CPU time of the same, summed over threads (per-thread clocks)
  double serial_ms = 0.0;    // of cpu_ms, the caller's thread outside parallel sections: the part
                             // threads cannot spread (on T cores a frame takes >= serial + (cpu - serial) / T)
  double span_ms = 0.0;      // serial_ms plus, per parallel step, its busiest worker's CPU: the frame's
                             // time on free cores, wake-ups aside (cpu_ms / span_ms: what the threads gained)

  void add(const SceneStats& o);  // sums counters and times (for totals over frames)
};

class Scene {
 public:
  // One shape per distinct (solid, time) (its own for an instance whose time
  // runs, "time_rate"), posed at frame 0. A shape's biarc tree is built when a
  // narrow-phase query first needs it: a scene's questions cost what they touch.
  Scene(const Case& c, const SceneOptions& options);

  std::size_t size() const { return model_.instances.size(); }
  // Instance i at the current frame (a deforming shape's tree is built now if
  // no query has needed it yet; not to be called from several threads at once).
  const PosedSolid& solid(std::size_t i) const;
  const Aabb& box(std::size_t i) const { return boxes_[i]; }
  const AabbTree& broad_phase() const { return tree_; }

  // Poses every instance at frame f (core/motion.h), blends and rebuilds the
  // shapes whose keyframe time runs, recomputes the boxes and refits the broad
  // phase (rebuilt when refitting has loosened it). Adds to st.
  void set_frame(double f, SceneStats* st);

  // Every pair whose distance is <= d (within = true) or not proven > d, sorted by (a, b).
  // More than kMaxWithinPairs pairs of boxes within d: an InputError, before any
  // narrow-phase call (each pair holds a result: 2e8 pairs ran out of memory).
  // With options.coherence, a pair may be settled from its bracket of an earlier
  // call (see SceneOptions), so brackets, not decisions, depend on the history.
  std::vector<ScenePair> within(double d, SceneStats* st);
  // The same into *out, reusing its elements' storage (a caller asking every
  // frame passes the same vector: no per-pair allocation once warmed up).
  // False, with *out empty and before any narrow-phase call, when more than
  // max_answers pairs are certainly within d (a surface point of each that
  // close): 2000 rings stacked in one place ran 2M queries (32 s) before the
  // caller could refuse their answers.
  bool within(double d, SceneStats* st, std::vector<ScenePair>* out,
              std::size_t max_answers = std::numeric_limits<std::size_t>::max());
  // The k pairs of smallest upper bound (full brackets), sorted by (upper, a, b).
  std::vector<ScenePair> closest(std::size_t k, SceneStats* st);
  // The k instances nearest to instance i (a = i), sorted by (upper, b).
  std::vector<ScenePair> nearest(std::size_t i, std::size_t k, SceneStats* st);

 private:
  struct LocalBound {  // a tree node's capsule: segment (r, z) - (r, z) and radius
    Vec2 a, b;
    double radius;
  };
  // What within(d) keeps of a pair for the next frame (SceneOptions::coherence).
  struct PairMemory {
    std::int32_t a = -1, b = -1;
    Mat3 R_ba;  // pose of a in b's frame when the bracket was computed
    Vec3 t_ba;
    double lower = 0.0;
    Vec3 p_a, p_b;  // witness points in a's and b's local frames
    bool valid = false;  // a bracket with witnesses, no overlap (overlaps are recomputed)
  };
  bool settle_from_memory(const PairMemory& m, double d, ScenePair* p) const;
  void fit_bounds(std::size_t shape);
  void hull_bounds(std::size_t shape);
  double build_stale(const std::vector<std::int32_t>& instances, SceneStats* st);
  // Builds shape k's tree (lazy where its time runs and lazy trees are asked);
  // returns its node count.
  long build_tree(std::size_t k) const;
  Aabb world_box(std::size_t i) const;
  SolidDistanceResult query(std::int32_t a, std::int32_t b, double threshold) const;
  template <class Stream>
  std::vector<ScenePair> best_k(Stream& stream, std::size_t k, SceneStats* st);

  SceneOptions options_;
  std::vector<Pose> pose0_;      // per instance, frame 0
  std::vector<InstanceMotion> motion_;  // per instance
  std::vector<double> time0_;           // per instance: keyframe time at frame 0
  std::vector<SolidDef> solids_;        // the case's, for shapes whose time runs
  // Per shape: its tree is not built for its profile (none yet, or a blend of
  // this frame): built when a narrow-phase query first needs it; boxes
  // meanwhile come from capsules around its control points (hull_bounds).
  mutable std::vector<char> stale_;
  std::vector<char> runs_;  // per shape: the shape of an instance whose keyframe time runs
  CaseModel model_;
  std::vector<std::vector<LocalBound>> bounds_;  // per shape
  std::vector<Aabb> boxes_;                      // per instance, world
  std::vector<double> reach_;                    // per shape: max |local point| of the solid
  std::vector<PairMemory> memory_;               // within(d)'s pairs of the last call, sorted by (a, b)
  std::vector<PairMemory> memory_next_;          // storage for the next call's
  std::vector<std::pair<std::int32_t, std::int32_t>> memory_keys_;  // memory_[k]'s (a, b)
  std::vector<std::int32_t> memory_first_;       // per instance a: its first entry in memory_ (size n + 1)
  // within(d)'s scratch, kept across calls (warm storage; strings keep their capacity).
  std::vector<std::pair<std::int32_t, std::int32_t>> cand_;
  std::vector<ScenePair> slots_;
  std::vector<char> keep_;
  std::vector<std::int32_t> at_;
  AabbTree tree_;
  mutable long unreported_nodes_ = 0;
};

}  // namespace revdist
