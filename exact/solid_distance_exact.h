// Certified minimum distance between two solids of revolution (SPEC sections 2
// and 6; the reference for paper section 4.2): an MPFI branch and bound over the
// exact input curves, independent of fast/ (no biarcs, no circle binormals). The
// method and why it is a proof are stated in exact/solid_distance_exact.cpp.
// This header includes no CGAL/GMP/MPFR header on purpose (the CLI includes it).
#pragma once
#include <functional>
#include <string>

#include "core/pose.h"
#include "core/profile.h"
#include "core/vec.h"

namespace revdist {

// What a long query has done so far (ExactSolidOptions::progress).
struct ExactProgress {
  long boxes = 0;                      // parameter boxes evaluated
  double lower = 0.0, upper = 0.0;     // the current proven bracket of the distance
  double target_width = 0.0;           // the width the query stops at
  double seconds = 0.0;                // wall time since the query started
};

struct ExactSolidOptions {
  // Target width of [lower, upper] relative to the scale of the query (the larger
  // of the two solids' sizes and the distance between their frame origins).
  double relative_width = 1e-9;
  double absolute_width = 0.0;  // > 0: the target width itself, instead of relative_width * scale
  long max_boxes = 2000000;     // work budget: parameter boxes evaluated
  // Work budget in thread CPU seconds (0: none), and a stop request asked every
  // 256 boxes: either ends the search with the bracket proven so far (reason
  // says which). (One degree-8 Bezier pair ran past 60 s within the box budget.)
  double max_cpu_s = 30.0;
  std::function<bool()> stop;
  // Off only to test the paths against each other: tube pairs by the circle
  // distance, and box bounds on outward-rounded doubles before MPFI.
  bool use_structure = true;
  bool double_bounds = true;
  // Called from the query's thread at most once per progress_interval_s of wall
  // time, never before the first interval has passed (short queries stay silent).
  std::function<void(const ExactProgress&)> progress;
  double progress_interval_s = 1.0;
};

struct ExactSolidResult {
  // true: lower <= d <= upper is PROVEN, d the distance between the solids as
  // given by their input curves (0 when they overlap or one contains the other).
  // false: nothing is proven (reason says why); lower/upper are then 0 and +inf.
  bool certified = false;
  std::string reason;            // certified: empty, or why the width target was not reached
  double lower = 0.0, upper = 0.0;  // doubles rounded outward from the proven interval
  bool width_reached = false;    // upper - lower <= the target width
  bool overlap = false;          // proven: a point lies strictly inside both solids (lower = upper = 0)
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();  // world points on the two surfaces, |a - b| ~ upper
  double scale = 0.0;
  long boxes = 0;                // parameter boxes evaluated (on doubles, and again on MPFI near contact)
  long mpfi_boxes = 0;           // boxes whose double bound was too loose near contact: re-bounded on MPFI
  int element_pairs = 0;         // pairs (element of a, element of b): the leaves of the search
  int closed_form_pairs = 0;     // pairs settled in closed form (tube against tube: circle distance)
  int circle_pairs = 0;          // circle pairs certified for those tube bounds (near-equal circles share one)
  int searched_pairs = 0;        // pairs that needed branch and bound
  double time_ms = 0.0;          // per-thread CPU time of the query
};

// The engine's elements of a profile (the Bezier segments of its pieces: core/curve_eval.h,
// piece_bezier_segments) and the most element pairs one query takes. Every pair is a job
// (a closed-form tube bound, then the search if it is not settled): two spheres of 500
// line pieces each take about 5 s, of 3000 took 238 s, of 30000 ran out of memory. A
// query past the limit is not certified (reason says why) and does no work.
long exact_elements(const Profile& profile);
inline constexpr long kMaxExactElementPairs = 250000;

// Distance between solid a (profile a, world = R(pose_a) local + t) and solid b.
// Deformable solids: pass the blended profile (core/case_io.h: profile_at).
// Never throws on valid profiles; a failure is data (certified = false).
ExactSolidResult solid_distance_exact(const Profile& a, const Pose& pose_a, const Profile& b, const Pose& pose_b,
                                      const ExactSolidOptions& options = {});

}  // namespace revdist
