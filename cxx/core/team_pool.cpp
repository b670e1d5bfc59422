// The stages' thread team (team_pool.hpp).
//
// A job is published as a sequence lock: `generation` goes odd while the caller writes the
// job's fields and even again once they are written; a worker that sees a new even
// generation reads the job and checks the generation again (a worker that took no part in
// the last job may still be reading when the next is written), runs it if its number is
// below the job's size, and counts itself out. A worker starts at the generation of its
// creation, so it never takes a job that ran before it. The caller runs its own share and
// waits until every other taker has counted out, so a job's fields are never rewritten while
// a taker reads them. Waiting spins on one cache line with a pause, then gives the core away:
// workers sleep on a condition variable after about a millisecond without a job, the caller
// and the barrier yield after about 50 us, so that a team on a busy machine does not spin
// while the thread it waits for has no core (the time loop's TeamChooser then runs steps on
// one thread).
#include "core/team_pool.hpp"

#include <sched.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace mpm3d {
namespace {

class Team;
thread_local int tl_thread = 0, tl_size = 1;
thread_local Team* tl_team = nullptr;  // the team of the running job (its barrier)

inline void cpu_pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Spins until done() holds: a pause a test, the clock read every 64 tests; past `budget`
// returns false (the caller then sleeps or yields).
template <class Done>
bool spin_until(Done&& done, std::chrono::microseconds budget) {
  const auto start = std::chrono::steady_clock::now();
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    cpu_pause();
    if ((i & 63u) == 0 && std::chrono::steady_clock::now() - start > budget) return false;
  }
}

// The CPUs this process may run on (its affinity mask; 0: unknown).
int usable_cpus() {
#ifdef __linux__
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return CPU_COUNT(&set);
#endif
  return int(std::thread::hardware_concurrency());
}

// Whether a team of `threads` may spin: not with more threads than CPUs, where the thread
// waited for may be the one without a core (3 threads on 2 CPUs spun 12 times as long).
bool may_spin(int threads) {
  static const int cpus = usable_cpus();
  return cpus <= 0 || threads <= cpus;
}

template <class Done>
void spin_then_yield(Done&& done, bool spin) {
  if (spin && spin_until(done, std::chrono::microseconds(50))) return;
  while (!done()) std::this_thread::yield();
}

class Team {
 public:
  ~Team() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_.store(true);
      generation_.fetch_add(2);
    }
    wake_.notify_all();
    for (std::thread& w : workers_) w.join();
  }

  void run(int threads, void (*fn)(void*), void* arg) {
    while (int(workers_.size()) < threads - 1) {
      const int number = int(workers_.size()) + 1;
      const unsigned now = generation_.load(std::memory_order_relaxed);
      workers_.emplace_back([this, number, now] { work(number, now); });
      workers_count_.store(int(workers_.size()), std::memory_order_relaxed);
    }
    const unsigned g = generation_.load(std::memory_order_relaxed);  // even: no job being written
    generation_.store(g + 1, std::memory_order_seq_cst);  // odd: the fields change
    std::atomic_thread_fence(std::memory_order_release);  // ... only after it is seen
    fn_.store(fn, std::memory_order_relaxed);
    arg_.store(arg, std::memory_order_relaxed);
    size_.store(threads, std::memory_order_relaxed);
    pending_.store(threads - 1, std::memory_order_relaxed);
    generation_.store(g + 2, std::memory_order_seq_cst);  // publishes the fields above
    if (sleepers_.load(std::memory_order_seq_cst) > 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      wake_.notify_all();
    }
    ++runs_;
    const auto start = std::chrono::steady_clock::now();
    tl_thread = 0;
    tl_size = threads;
    tl_team = this;
    fn(arg);
    spin_then_yield([&] { return pending_.load(std::memory_order_acquire) == 0; }, may_spin(threads));
    tl_size = 1;
    tl_team = nullptr;
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void barrier() {
    const int size = tl_size;
    if (size <= 1) return;
    const unsigned phase = barrier_phase_.load(std::memory_order_acquire);
    if (barrier_count_.fetch_add(1, std::memory_order_acq_rel) == size - 1) {
      barrier_count_.store(0, std::memory_order_relaxed);
      barrier_phase_.fetch_add(1, std::memory_order_release);
      return;
    }
    spin_then_yield([&] { return barrier_phase_.load(std::memory_order_acquire) != phase; }, may_spin(size));
  }

  long runs() const { return runs_; }
  double seconds() const { return seconds_; }

 private:
  void work(int number, unsigned seen) {
    for (;;) {
      auto fresh = [&] {
        const unsigned g = generation_.load(std::memory_order_acquire);
        return g != seen && (g & 1u) == 0;
      };
      const bool spin = may_spin(int(workers_count_.load(std::memory_order_relaxed)) + 1);
      if (!(spin && spin_until(fresh, std::chrono::milliseconds(1))) && !fresh()) {
        sleepers_.fetch_add(1, std::memory_order_seq_cst);
        {
          std::unique_lock<std::mutex> lock(mutex_);
          wake_.wait(lock, fresh);
        }
        sleepers_.fetch_sub(1, std::memory_order_relaxed);
      }
      const unsigned g = generation_.load(std::memory_order_acquire);
      if (stop_.load()) return;
      if ((g & 1u) != 0) continue;  // a job being written
      void (*fn)(void*) = fn_.load(std::memory_order_relaxed);
      void* arg = arg_.load(std::memory_order_relaxed);
      const int size = size_.load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (generation_.load(std::memory_order_relaxed) != g) continue;  // a newer job: read that one
      seen = g;
      if (number >= size) continue;  // not one of this job's threads
      tl_thread = number;
      tl_size = size;
      tl_team = this;
      fn(arg);
      tl_thread = 0;
      tl_size = 1;
      tl_team = nullptr;
      pending_.fetch_sub(1, std::memory_order_acq_rel);
    }
  }

  // The job and its hand-over, each on its own cache line.
  alignas(64) std::atomic<unsigned> generation_{0};
  std::atomic<void (*)(void*)> fn_{nullptr};
  std::atomic<void*> arg_{nullptr};
  std::atomic<int> size_{1};
  alignas(64) std::atomic<int> pending_{0};
  alignas(64) std::atomic<int> barrier_count_{0};
  alignas(64) std::atomic<unsigned> barrier_phase_{0};
  alignas(64) std::atomic<int> sleepers_{0};
  std::atomic<bool> stop_{false};
  std::atomic<int> workers_count_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<std::thread> workers_;  // touched by the caller's thread only
  long runs_ = 0;
  double seconds_ = 0.0;
};

// One team for each thread that runs stages (two simulations in two threads of a program
// each have their own).
Team& team() {
  static thread_local Team t;
  return t;
}

}  // namespace

void team_run(int threads, void (*fn)(void*), void* arg) {
  if (threads <= 1 || tl_size > 1) {  // one thread, or nested: this thread alone
    const int t = tl_thread, s = tl_size;
    tl_thread = 0;
    tl_size = 1;
    fn(arg);
    tl_thread = t;
    tl_size = s;
    return;
  }
  team().run(threads, fn, arg);
}

void team_barrier() {
  if (tl_size > 1) tl_team->barrier();
}

int team_thread() { return tl_thread; }
int team_size() { return tl_size; }
long team_runs() { return team().runs(); }
double team_seconds() { return team().seconds(); }

}  // namespace mpm3d
