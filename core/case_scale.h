// The size of a case and the limits of eps and tol that follow from it (issue 10 items
// 5, 6): eps and tol are absolute lengths, but below a fixed fraction of the model's
// coordinates they are lost in double rounding, and the work to chase them is unbounded.
#pragma once
#include <string>

#include "core/profile.h"

namespace revdist {

struct CaseScale {
  double size = 0;          // largest profile size (bounding-box diagonal) over all solids and keyframes
  double extent = 0;        // largest of size and |coordinate| over all profiles
  double query_extent = 0;  // largest |translation| + extent of the instances that queries use
};

CaseScale case_scale(const Case& c);
// One solid's extent: the largest of its profiles' sizes and |coordinates| over
// every keyframe (CaseScale::extent is the largest over the solids).
double solid_extent(const SolidDef& s);

// Fits finer than this are below what the spiral split and the lens proof can resolve in
// doubles: measured on the paper models (size ~1.6), eps = 3e-14 still builds and
// 1e-14 exhausts memory; the limit keeps a factor ~50 above that edge.
constexpr double kMinRelativeEps = 1e-12;
// Brackets narrower than this cannot be met: world coordinates round at about
// 1.1e-16 of query_extent and the bounds carry allowances for it; measured on the paper
// pairs, the narrowest reachable bracket is ~6e-14 of query_extent.
constexpr double kMinRelativeTol = 2e-13;

inline double min_eps(const CaseScale& s) { return kMinRelativeEps * s.extent; }
// InputError naming `who` when eps < kMinRelativeEps * extent (distance, fit, scene, compare, bench).
void require_resolvable_eps(double eps, double extent, const std::string& who);
inline double min_tol(const CaseScale& s) { return kMinRelativeTol * s.query_extent; }
// InputError naming `who` when tol < kMinRelativeTol * query_extent (distance, scene, compare).
void require_resolvable_tol(double tol, double query_extent, const std::string& who);

// The unit that scales the default eps and tol: 1 for models whose largest profile size
// lies in [1e-2, 1e2] (the defaults were chosen for those), otherwise that size, so a
// model of size 1e-20 or 1e8 gets the same relative bracket and bounded work.
inline double default_unit(const CaseScale& s) { return s.size >= 1e-2 && s.size <= 1e2 ? 1.0 : s.size; }

}  // namespace revdist
