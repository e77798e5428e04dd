// Minimum distance between two posed solids of revolution (paper section 4.2,
// Algorithm 2) with proven bounds (SPEC section 6): a priority-queue traversal
// of the two biarc trees, lower bounds from the trees' bounding tori and from
// exact patch distances minus the proven fit errors, upper bounds from witness
// points on the true (input) surfaces, and local refinement of the fits near
// the closest pair when the tolerance asks for more than the trees give.
#pragma once
#include <limits>
#include <string>

#include "core/profile.h"
#include "fast/biarc_tree.h"

namespace revdist {

// A solid in the world: its input profile (the true surface), its biarc tree,
// and its pose x_world = R * x_local + t. The profile and tree are read only,
// so any number of queries may share them across threads.
struct PosedSolid {
  const Profile* profile = nullptr;
  const BiarcTree* tree = nullptr;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
};

struct DistanceOptions {
  double tol = 1e-6;            // stop when upper - lower <= tol (absolute length)
  // Also stop when upper - lower <= rel_tol * lower (digits rather than units);
  // 0 disables. Converged means either tolerance is met.
  double rel_tol = 0.0;
  // Threshold predicate ("closer than threshold?"): when finite, the query
  // stops as soon as upper <= threshold (closer) or lower > threshold (not),
  // without narrowing the bracket further; SolidDistanceResult::decided says so.
  double threshold = std::numeric_limits<double>::quiet_NaN();
  int max_refine = 24;          // subdivision levels allowed below a tree leaf
  // Work budget; beyond either the result says converged = false and which ran
  // out. Patch-pair kernels are the costly unit (~30 us each, up to ~140 us on
  // near-degenerate cone pairs): 10,000 of them end a query within ~1.5 s.
  // Leaf pairs (fit pairs compared) cost more the more a query has (each
  // scans the bounds of those before it for its neighbours'): bottle-bottle2
  // at eps 1e-11 needs 15,000 (0.6 s, 14 us each), so 25,000 is ~1.5 s.
  long max_node_pairs = 1000000;
  long max_patch_pairs = 10000;
  long max_leaf_pairs = 25000;
};

struct DistanceStats {
  long node_pairs = 0;   // pairs popped from the queue and processed (descended or compared)
  long hull_parts = 0;   // popped pairs retired by their capsules' hulls (revolved_hull_bound), before splitting or a tight bound
  long bounds = 0;       // tight bounds computed for pairs of fits (pairs are queued with a closed-form one)
  long leaf_pairs = 0;   // pairs of fits whose patches were compared
  long patch_pairs = 0;  // full patch-patch evaluations (fast/patch_distance.h): the local proof's fallbacks
  long local_pairs = 0;  // patch pairs settled by the local proof (patches_at_least)
  long local_boxes = 0;  // boxes the local proof evaluated (settled or not)
  long hull_pairs = 0;   // patch pairs settled by their revolved arcs' hulls (patch_hull_bound), first
  long spine_pairs = 0;  // patch pairs settled by a spine bound (patch_spine_at_least), before the local proof
  long node_fit_parts = 0;  // popped pairs of fine trees retired by their nodes' own fits (node_fits_bound)
  long zone_parts = 0;   // popped pairs retired by a fit's sphere zones or cylinders (their axis pieces' distances less the radii)
  long spine_parts = 0;  // popped pairs of a fit and a part 4x smaller given the fit's spine bound (retired or not)
  long spine_evals = 0;  // points of the spines the spine bounds evaluated (settled or not)
  long quick_pairs = 0;  // patch pairs settled by the cheap look (pruned or exact)
  long refined = 0;      // parts created by refining fits below the tree leaves
  long nodes_built = 0;  // lazy trees: nodes this query built (0 for eager trees)
};

struct SolidDistanceResult {
  double lower = 0.0, upper = 0.0, distance = 0.0;
  bool overlap = false;    // proven: the solids share a point (then lower = upper = 0)
  bool converged = false;  // upper - lower <= tol (or <= rel_tol * lower)
  bool decided = false;    // a threshold query was settled (lower > threshold or upper <= threshold)
  std::string reason;      // why not converged
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();  // on the true surfaces (world)
  DistanceStats stats;
};

SolidDistanceResult solid_distance(const PosedSolid& a, const PosedSolid& b, const DistanceOptions& options = {});

// Frame coherence for a sequence of poses of the same two solids (smooth
// motion): what one query keeps for the next, its answer's points in each
// solid's own frame. The next query checks them against the solids at their
// new poses (a point not in its solid, to rounding, is ignored, so a stale or
// foreign warm start costs two point tests and never changes an answer's
// guarantees): the two points give an upper bound before the traversal, and
// after an overlap the shared point, still inside the other solid, proves the
// overlap at once.
struct WarmStart {
  bool valid = false;
  bool overlap = false;
  Vec3 a_local = Vec3::Zero(), b_local = Vec3::Zero();
};
// The warm start a result leaves for the next pose (a and b: the poses it was
// computed at). Invalid when the result's upper bound is not finite (no
// candidate pair); whatever it holds, the next query checks its points.
WarmStart warm_start_of(const SolidDistanceResult& r, const PosedSolid& a, const PosedSolid& b);
SolidDistanceResult solid_distance(const PosedSolid& a, const PosedSolid& b, const DistanceOptions& options,
                                   const WarmStart& warm);

}  // namespace revdist
