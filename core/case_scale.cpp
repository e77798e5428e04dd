// Size of a case for the eps and tol limits (see case_scale.h).
#include "core/case_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/format.h"
#include "core/input_error.h"
#include "core/profile_check.h"

namespace revdist {

double solid_extent(const SolidDef& s) {
  double extent = 0.0;
  for (const Profile& p : s.keyframes) {
    if (p.pieces.empty()) continue;
    Vec2 lo, hi;
    profile_box(p, &lo, &hi);
    extent = std::max({extent, (hi - lo).norm(), lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()});
  }
  return extent;
}

// (The minimum is printed rounded up: the value printed is one that passes.)
void require_resolvable_eps(double eps, double extent, const std::string& who) {
  if (eps >= kMinRelativeEps * extent) return;
  throw InputError(who + ": --eps " + fixed_digits(eps, 6) + " is below the smallest meaningful value " +
                   digits_up(kMinRelativeEps * extent, 3) + " (" + fixed_digits(kMinRelativeEps, 3) +
                   " of the solid extent " + fixed_digits(extent, 6) + "; finer fits are lost in rounding)");
}

void require_resolvable_tol(double tol, double query_extent, const std::string& who) {
  if (tol >= kMinRelativeTol * query_extent) return;
  throw InputError(who + ": --tol " + fixed_digits(tol, 6) + " is below the smallest meaningful value " +
                   digits_up(kMinRelativeTol * query_extent, 3) + " (" + fixed_digits(kMinRelativeTol, 3) +
                   " of the queries' extent " + fixed_digits(query_extent, 6) +
                   ", |translation| + solid extent; narrower brackets are lost in rounding)");
}

CaseScale case_scale(const Case& c) {
  CaseScale s;
  std::vector<double> extent(c.solids.size(), 0.0);
  for (std::size_t i = 0; i < c.solids.size(); ++i) {
    for (const Profile& p : c.solids[i].keyframes) s.size = std::max(s.size, profile_size(p));
    extent[i] = solid_extent(c.solids[i]);
    s.extent = std::max(s.extent, extent[i]);
  }
  std::vector<bool> used(c.instances.size(), false);
  for (const auto& q : c.queries) used[q.first] = used[q.second] = true;
  for (std::size_t i = 0; i < c.instances.size(); ++i) {
    if (!used[i]) continue;
    const Instance& inst = c.instances[i];
    s.query_extent = std::max(s.query_extent, inst.pose.translation.norm() + extent[inst.solid]);
  }
  return s;
}

}  // namespace revdist
