// Independent tasks on a few threads: the one way splinecal runs work in parallel outside Ceres
// (the EuRoC reader's chunks, the compressed information's residual blocks).
#ifndef SPLINECAL_RUN_TASKS_H_
#define SPLINECAL_RUN_TASKS_H_

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace splinecal {

// Runs task(0) .. task(count - 1) on up to `threads` threads (the calling one included), each
// thread taking the next task when it is done with one; returns when all are done. The first
// exception a task throws stops the tasks not yet started and is rethrown here. Tasks must not
// depend on their order; which thread runs which task varies from run to run.
template <typename Task>
void RunTasks(int threads, int64_t count, Task&& task) {
  std::atomic<int64_t> next{0};
  std::mutex mutex;
  std::exception_ptr failure;
  auto work = [&]() {
    try {
      for (int64_t i = next++; i < count; i = next++) task(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (int64_t i = 1; i < std::min<int64_t>(threads, count); ++i) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads: the ones started do the work
    }
  }
  work();
  for (std::thread& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace splinecal

#endif  // SPLINECAL_RUN_TASKS_H_
