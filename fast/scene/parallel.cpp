// std::thread work sharing with per-thread CPU accounting.
#include "fast/scene/parallel.h"

#include <algorithm>
#include <atomic>
#include <ctime>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace revdist {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& fn) {
  const std::size_t workers = std::max<std::size_t>(1, std::min<std::size_t>(threads < 1 ? 1 : threads, n));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<double> cpu(workers, 0.0);
  // Small chunks: narrow-phase pairs differ in cost by orders of magnitude.
  const std::size_t chunk = std::max<std::size_t>(1, std::min<std::size_t>(16, n / (8 * workers)));
  auto work = [&](std::size_t w) {
    const double t0 = thread_cpu_seconds();
    try {
      for (;;) {
        const std::size_t begin = next.fetch_add(chunk);
        if (begin >= n || failed.load(std::memory_order_relaxed)) break;
        for (std::size_t i = begin; i < std::min(n, begin + chunk); ++i) fn(i);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
    cpu[w] = thread_cpu_seconds() - t0;
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  double sum = 0.0;
  for (std::size_t w = 1; w < workers; ++w) sum += cpu[w];
  return sum;
}

}  // namespace revdist
