#pragma once
/// Exceptions out of OpenMP regions. A C++ exception that leaves a `#pragma omp parallel`
/// region (or an `omp task`) calls std::terminate: the program aborts instead of reporting
/// the InputError/Error that was thrown (core/error.hpp). ParallelFailure catches inside the
/// region and rethrows after it:
///
///     ParallelFailure failure;
///     #pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
///     for (int i = 0; i < n; ++i)
///       failure.run(i, [&] { work(i); });
///     failure.rethrow();  // the exception of the lowest index i, if any
///
/// - Deterministic: of several iterations that throw, the one of the lowest index wins, on any
///   thread count, so the error is the one a serial loop would have thrown first.
/// - The other iterations run to the end unharmed (no iteration is skipped): the region's
///   outputs are those of a loop without the failing iterations, then the error is thrown.
/// - Zero-cost when nothing throws (table-based unwinding: the try block adds no instruction
///   on the normal path). For loops over cheap items, wrap a chunk of consecutive items and
///   pass the chunk's index: a serial chunk throws at its first failing item.
/// - Thread-safe: run() and record() may be called from any thread of the team at once;
///   rethrow() and failed() after the region (failed() also inside it, as a hint to stop).
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <utility>

namespace ablmg {

class ParallelFailure {
 public:
  /// Calls f(); an exception f throws is kept (if `index` is the lowest failing index so far)
  /// instead of propagating. `index` orders failures: the loop index, or a chunk index.
  template <class F>
  void run(long index, F&& f) noexcept {
    try {
      std::forward<F>(f)();
    } catch (...) { record(index, std::current_exception()); }
  }

  /// Records a failure at `index` (call from a catch block: `record(i, std::current_exception())`).
  void record(long index, std::exception_ptr error) noexcept {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!error_ || index < index_) {
      index_ = index;
      error_ = std::move(error);
    }
    failed_.store(true, std::memory_order_relaxed);
  }

  /// Whether any iteration failed so far.
  bool failed() const noexcept { return failed_.load(std::memory_order_relaxed); }

  /// The lowest failing index (LONG_MAX when none failed). After the region.
  long index() const noexcept { return error_ ? index_ : std::numeric_limits<long>::max(); }

  /// After the region: rethrows the exception of the lowest failing index; nothing if none.
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex mutex_;
  std::atomic<bool> failed_{false};
  long index_ = std::numeric_limits<long>::max();
  std::exception_ptr error_;
};

}  // namespace ablmg
