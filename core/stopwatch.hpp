#pragma once
/// Wall-clock timing of the pipeline's stages, in seconds (std::chrono::steady_clock: monotonic,
/// unaffected by changes of the system time).
///
///   Stopwatch watch;                     // starts now
///   ...; stats.secondsRead = watch.lap();  // seconds since start, and restarts
///   { ScopedTimer t(stats.secondsRepair); repair(); }  // adds the scope's seconds
///
/// Timings are reported, never used to decide anything: outputs do not depend on them.
#include <chrono>

namespace ablmg {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;
  Stopwatch() : start_(Clock::now()) {}
  /// Seconds since construction or the last restart()/lap().
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  /// seconds(), then restarts: consecutive laps time consecutive stages.
  double lap() {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }
  void restart() { start_ = Clock::now(); }

 private:
  Clock::time_point start_;
};

/// Adds the seconds between its construction and its destruction to `total`.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total) {}
  ~ScopedTimer() { total_ += watch_.seconds(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  Stopwatch watch_;
};

}  // namespace ablmg
