// Size of a case for the eps and tol limits (see case_scale.h).
#include "core/case_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/profile_check.h"

namespace revdist {

CaseScale case_scale(const Case& c) {
  CaseScale s;
  std::vector<double> extent(c.solids.size(), 0.0);
  for (std::size_t i = 0; i < c.solids.size(); ++i) {
    for (const Profile& p : c.solids[i].keyframes) {
      const double size = profile_size(p);
      s.size = std::max(s.size, size);
      extent[i] = std::max(extent[i], size);
      for (const Piece& piece : p.pieces)
        for (const Vec2& q : piece.points) extent[i] = std::max({extent[i], std::abs(q.x()), std::abs(q.y())});
    }
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
