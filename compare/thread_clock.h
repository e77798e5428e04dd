// Per-thread CPU time, the clock every timing in compare/ reports (the machine
// is shared: wall time can be several times off), and the nearest-rank
// percentile the bench summarises it with.
#pragma once
#include <time.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace revdist {

// CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID), microseconds.
inline double thread_cpu_us() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
}

// Nearest-rank percentile (q in (0, 1]) of the samples; NaN when there are none.
inline double nearest_rank_percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t k = static_cast<std::size_t>(std::ceil(q * v.size()));
  return v[std::min(v.size() - 1, k > 0 ? k - 1 : 0)];
}

}  // namespace revdist
