#pragma once
/// CHOLMOD's own OpenMP loops, run by the calling thread alone while a CholmodScope lives.
///
/// Debian's CHOLMOD (SuiteSparse 5) is built with `num_threads(4)` on the small loops of its
/// supernodal factorisation and solves (zeroing a supernode, scattering A into it, clearing
/// the row map): one OpenMP team per supernode, whatever OMP_NUM_THREADS says. Those loops
/// are memory-bound copies of a few thousand entries; on 2 cores the team costs more than the
/// loop (under OMP_WAIT_POLICY=passive every team is a round of futex wake-ups: ≈ 1.5·10⁵
/// per 10⁵-unknown solve), and on a loaded machine each waits for descheduled helpers.
/// The scope sets the calling thread's max-active-levels ICV to 0 (a per-task value: other
/// threads' parallel regions are unaffected), so every region CHOLMOD opens from this thread
/// runs with a team of one; the destructor restores the previous value. The loops compute
/// the same values either way: results are bitwise unchanged.
#include <omp.h>

namespace ablmg::fem {

class CholmodScope {
 public:
  CholmodScope() : saved_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~CholmodScope() { omp_set_max_active_levels(saved_); }
  CholmodScope(const CholmodScope&) = delete;
  CholmodScope& operator=(const CholmodScope&) = delete;

 private:
  int saved_;
};

}  // namespace ablmg::fem
