// std::thread work sharing with per-thread CPU accounting. Workers persist
// across calls (a scene frame makes several calls; spawning threads each time
// cost clone + stack faults + a cold malloc cache per call), and each worker
// starts on its own contiguous block of indices with a cursor of its own
// (instance and sorted-pair indices are neighbours in space, so a worker keeps
// touching the same solids), stealing from the other blocks when its own runs out.
#include "fast/scene/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <ctime>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace revdist {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

namespace {

using WorkerFn = std::function<void(std::size_t, std::size_t)>;

thread_local double parallel_seconds = 0.0;  // thread_parallel_seconds()
thread_local double span_seconds = 0.0;      // thread_span_seconds()
thread_local int call_depth = 0;             // parallel_for calls under way on this thread

class Job {
 public:
  Job(std::size_t n, std::size_t workers, const WorkerFn& fn) : fn_(fn), blocks_(workers), cpu_(workers, 0.0) {
    for (std::size_t w = 0; w < workers; ++w) {
      blocks_[w].next.store(n * w / workers, std::memory_order_relaxed);
      blocks_[w].end = n * (w + 1) / workers;
    }
    // Small chunks: narrow-phase pairs differ in cost by orders of magnitude
    // (a chunk of 16 pairs near the threshold is milliseconds of one worker at
    // the end of a step); a worker's own cursor is not contended until stealing.
    chunk_ = std::max<std::size_t>(1, std::min<std::size_t>(4, n / (8 * workers)));
  }
  std::size_t workers() const { return blocks_.size(); }

  void work(std::size_t w) {
    const double t0 = thread_cpu_seconds();
    try {
      for (std::size_t k = 0; k < blocks_.size() && !failed_.load(std::memory_order_relaxed); ++k) {
        Block& b = blocks_[(w + k) % blocks_.size()];
        for (;;) {
          const std::size_t begin = b.next.fetch_add(chunk_, std::memory_order_relaxed);
          if (begin >= b.end || failed_.load(std::memory_order_relaxed)) break;
          for (std::size_t i = begin; i < std::min(b.end, begin + chunk_); ++i) fn_(i, w);
        }
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
    }
    cpu_[w] = thread_cpu_seconds() - t0;
  }

  // Rethrows the first failure; else the CPU seconds of the workers besides the caller's.
  double finish() const {
    if (error_) std::rethrow_exception(error_);
    if (call_depth == 1) span_seconds += *std::max_element(cpu_.begin(), cpu_.end());
    double sum = 0.0;
    for (std::size_t w = 1; w < cpu_.size(); ++w) sum += cpu_[w];
    return sum;
  }

 private:
  struct alignas(64) Block {  // a cache line each: workers do not share cursors until they steal
    std::atomic<std::size_t> next{0};
    std::size_t end = 0;
  };
  const WorkerFn& fn_;
  std::vector<Block> blocks_;
  std::size_t chunk_ = 1;
  std::vector<double> cpu_;
  std::atomic<bool> failed_{false};
  std::mutex error_mutex_;
  std::exception_ptr error_;
};

// Threads that sleep between jobs. One job at a time: a caller that finds
// the pool busy (another thread's job) runs with threads of its own.
class Pool {
 public:
  static Pool& instance() {
    static Pool pool;
    return pool;
  }
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  // Runs job on the caller's thread (worker 0) and job.workers() - 1 pool
  // threads; false, having run nothing, if the pool is busy.
  bool run(Job& job) {
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> lock(m_);
      while (threads_.size() + 1 < job.workers()) {
        const std::size_t w = threads_.size() + 1;
        threads_.emplace_back([this, w] { loop(w); });
      }
      job_ = &job;
      pending_ = job.workers() - 1;
      ++generation_;
    }
    wake_.notify_all();
    job.work(0);
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return pending_ == 0; });
    job_ = nullptr;
    return true;
  }

 private:
  void loop(std::size_t w) {
    unsigned long seen = 0;
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || (job_ && generation_ != seen && w < job_->workers()); });
      if (stop_) return;
      seen = generation_;
      Job* job = job_;
      lock.unlock();
      job->work(w);
      lock.lock();
      if (--pending_ == 0) done_.notify_one();
    }
  }

  std::mutex busy_;  // held by the caller whose job the pool runs
  std::mutex m_;     // guards the fields below
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;  // worker w is threads_[w - 1]
  Job* job_ = nullptr;
  unsigned long generation_ = 0;
  std::size_t pending_ = 0;
  bool stop_ = false;
};

thread_local bool in_pool_job = false;  // nested calls run on threads of their own

// Adds the calling thread's CPU time in its outermost parallel_for call to parallel_seconds.
class CallClock {
 public:
  CallClock() : t0_(call_depth++ == 0 ? thread_cpu_seconds() : -1.0) {}
  ~CallClock() {
    --call_depth;
    if (t0_ >= 0) parallel_seconds += thread_cpu_seconds() - t0_;
  }

 private:
  double t0_;
};

double run_job(std::size_t n, int threads, const WorkerFn& fn) {
  const CallClock clock;
  const std::size_t workers = std::max<std::size_t>(1, std::min<std::size_t>(threads < 1 ? 1 : threads, n));
  Job job(n, workers, fn);
  if (workers == 1) {
    job.work(0);
    return job.finish();
  }
  if (!in_pool_job) {
    in_pool_job = true;
    const bool ran = Pool::instance().run(job);
    in_pool_job = false;
    if (ran) return job.finish();
  }
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back([&job, w] { job.work(w); });
  job.work(0);
  for (std::thread& t : pool) t.join();
  return job.finish();
}

}  // namespace

double thread_parallel_seconds() { return parallel_seconds; }

double thread_span_seconds() { return span_seconds; }

double parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& fn) {
  return run_job(n, threads, [&fn](std::size_t i, std::size_t) { fn(i); });
}

double parallel_for_workers(std::size_t n, int threads, const WorkerFn& fn) { return run_job(n, threads, fn); }

}  // namespace revdist
