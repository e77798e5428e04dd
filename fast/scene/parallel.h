// Work sharing for scene queries: persistent std::thread workers; each index
// writes only its own slot, so the answers do not depend on the number of
// threads or on scheduling.
#pragma once
#include <cstddef>
#include <functional>

namespace revdist {

// Calls fn(i) for every i in [0, n) on `threads` threads (the caller's thread
// is one of them). Returns the CPU seconds the other workers used, summed
// (CLOCK_THREAD_CPUTIME_ID per worker); the caller measures its own thread. The first exception thrown by fn is
// rethrown here once every worker has stopped.
double parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& fn);

// As above, fn(i, w) also gets the worker w in [0, threads) running it (0 is
// the caller), for per-worker accumulators; which w runs which i varies from
// call to call, so only order-independent sums may be kept per worker.
double parallel_for_workers(std::size_t n, int threads, const std::function<void(std::size_t, std::size_t)>& fn);

// CPU seconds used so far by the calling thread.
double thread_cpu_seconds();

// Of those, the seconds spent inside the parallel_for calls it made (the
// outermost ones, whatever their thread count): the rest of its work is what
// more threads cannot share.
double thread_parallel_seconds();

// Over the same calls, the sum of each call's largest per-worker CPU time:
// with the serial part, what the calls would take on as many free cores
// (a measure of imbalance that a loaded machine does not distort much, as
// stealing splits the work by how fast the workers progress).
double thread_span_seconds();

}  // namespace revdist
