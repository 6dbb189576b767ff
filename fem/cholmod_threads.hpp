#pragma once
/// CHOLMOD's own OpenMP loops, run by the calling thread alone while a CholmodScope lives, and
/// its BLAS calls on small blocks, run in-line (smallBlasCallCount below); the BLAS thread
/// policy and the factorisation settings of fem/.
///
/// Debian's CHOLMOD (SuiteSparse 5) is built with `num_threads(4)` on the small loops of its
/// supernodal factorisation and solves (zeroing a supernode, scattering A into it, clearing
/// the row map): one OpenMP region per supernode and per descendant, whatever OMP_NUM_THREADS
/// says (5.3·10⁵ regions in a 10⁶-unknown factorisation). Those loops are memory-bound copies
/// of a few thousand entries; on 2 cores a team costs more than the loop, and on a loaded
/// machine each waits for descheduled helpers. So a CholmodScope does two things:
///  - it sets the calling thread's max-active-levels ICV to 0 (a per-task value: other
///    threads' parallel regions are unaffected), so every region CHOLMOD opens from this
///    thread gets a team of one; the destructor restores the previous value;
///  - while it lives on a thread that is in no parallel region (omp_get_level() == 0), the
///    regions CHOLMOD opens run their body directly on that thread, without a team
///    (fem/cholmod_threads.cpp replaces libgomp's entry point GOMP_parallel, which CHOLMOD
///    calls, and forwards every other call to it). A team of one costs a team allocation
///    and two futex system calls (libgomp wakes its barrier's waiters even when there are
///    none): 1.05·10⁶ system calls in the 10⁶ factorisation, 0.7 s of its 1.9 s numeric phase
///    on the 2-core benchmark machine (docs/benchmarks.md, "P1 solver"). The body run
///    alone is the team of one's work exactly: with no team omp_get_num_threads() is 1 and
///    omp_get_thread_num() 0, so each worksharing loop takes all its iterations, and its
///    barriers return at once. Inside any parallel region (level ≥ 1) the call goes to the
///    runtime as before, since the body would then see the enclosing team's size.
/// The loops compute the same values either way: results are bitwise unchanged.
///
/// fixBlasThreads(): the one BLAS policy of every CHOLMOD factorisation and solve in fem/
/// (solve.cpp, heat.cpp): OpenBLAS runs with kBlasThreads = 1 thread, whatever
/// OMP_NUM_THREADS or OPENBLAS_NUM_THREADS say. Two reasons:
///  - OpenBLAS's threaded dpotrf blocks, hence rounds, differently for each thread count
///    (measured: the 10⁵- and 10⁶-unknown solves give other bits with 2, 3 and 4 threads), so
///    only a count fixed in code gives the same u_h, and the same adapted mesh, everywhere;
///  - a supernodal factorisation of a 2-D P1 matrix is thousands of small BLAS calls, on
///    which OpenBLAS's pthread pool wakes and spins (sched_yield): on a shared machine a call
///    waits for a descheduled helper (a 33k-unknown adapted mesh took 10–30 s wall for 0.26
///    GFlop in the adaptive loop). Two threads fixed in code, tried at 10⁵ and 10⁶ unknowns
///    on a loaded 2-core machine, took 1.2–1.7× the CPU of one thread and no less wall time.
#include <cholmod.h>
#include <omp.h>

// OpenBLAS's thread-count setter, if the BLAS loaded at run time is OpenBLAS (weak: null
// otherwise, e.g. with the reference BLAS, which is single-threaded anyway).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace ablmg::fem {

inline constexpr int kBlasThreads = 1;

/// Sets OpenBLAS to kBlasThreads threads (process-wide; a no-op without OpenBLAS).
inline void fixBlasThreads() {
  if (openblas_set_num_threads) openblas_set_num_threads(kBlasThreads);
}

/// A 2-D P1 factor has many small supernodes; each opens a few OpenMP regions (run without a
/// team inside a CholmodScope, above) and makes a handful of small BLAS calls (run in-line,
/// below). The two settings weigh that per-supernode cost against the flops and the stored
/// zeros, both chosen by CHOLMOD's own symbolic counts (deterministic: the same matrix takes
/// the same path):
///  - supernodal = CHOLMOD_AUTO: a simplicial (up-looking) factorisation when the flops
///    per factor entry are below CHOLMOD's supernodal_switch (40), i.e. when the fronts are
///    too small for BLAS to pay. The tanh layer's adapted mesh (8.7·10⁴ unknowns, 0.05 GFlop,
///    flops/nnz 30) takes it: 0.18 → 0.12 s CPU; the uniform and wave-front meshes (170–210)
///    and the 10⁶ grid stay supernodal. final_ll: the simplicial path computes LLᵀ, whose
///    non-positive pivot is an error (LDLᵀ would accept an indefinite matrix).
///  - nrelax = {4, 16, 48}, CHOLMOD's defaults, set here so that another SuiteSparse keeps
///    them: relaxed amalgamation merges small supernodes, allowing explicit zeros. Wider
///    merges ({16, 64, 256}, then {8, 32, 128}) paid while each supernode cost an OpenMP team
///    and a few OpenBLAS calls of ≈ 1.5 µs; with the regions run without a team and the small
///    BLAS calls in-line (below), the zeros cost more than the supernodes: every stored zero is
///    memory first written, which a virtual machine charges in page faults. {8, 32, 128} → {4, 16, 48}:
///    the final meshes of the library's ten adaptive loops (6–11·10⁴ unknowns, `ablmg solve`,
///    best of five alternated runs) 0.92–1.01× the solve time, geometric mean 0.97; the 10⁶ grid
///    with assembly 1.79–1.87 → 1.60–1.76 s (numeric 0.81–0.86 → 0.75–0.78 s); the 10⁵ meshes of
///    bench_solve_graded within 3 % either way (docs/experiments.md).
/// Used by every Poisson factorisation (fem/solve.cpp, fem/split_cholesky.cpp). Measured with
/// bench/bench_solve_graded.cpp (docs/benchmarks.md, "Solver ordering").
inline void configureFactorisation(cholmod_common& c) {
  c.supernodal = CHOLMOD_AUTO;
  c.final_ll = 1;
  c.nrelax[0] = 4;
  c.nrelax[1] = 16;
  c.nrelax[2] = 48;
}

class CholmodScope {
 public:
  CholmodScope();
  ~CholmodScope();
  CholmodScope(const CholmodScope&) = delete;
  CholmodScope& operator=(const CholmodScope&) = delete;

 private:
  int saved_;
};

/// How many OpenMP regions the calling thread has run without a team (inside a CholmodScope,
/// in no parallel region) since it started: the check that the shortcut above is in place
/// (tests/fem/test_solve.cpp; 0 when the program's GOMP_parallel is the runtime's own).
long teamlessRegionCount();

/// How many BLAS calls of CHOLMOD's (and fem/'s) the calling thread has run through the loops of
/// fem/small_blas.hpp since it started. This file defines dgemm_, dsyrk_, dtrsm_, dpotrf_,
/// dtrsv_ and dgemv_, which the dynamic linker resolves ahead of the BLAS: inside a
/// CholmodScope, a call of the shape CHOLMOD's supernodal factorisation and solves make (C = A Bᵀ,
/// lower(C) = A Aᵀ, B := B L⁻ᵀ, L Lᵀ = A, x := L⁻¹ x or L⁻ᵀ x, y += α A x or α Aᵀ x) on a block of
/// at most smallblas::kSmallWork multiply-adds runs those loops; any other call, and every call
/// outside a scope, goes to the BLAS. 0 when the program's definitions are not the ones in use
/// (e.g. a module loaded with RTLD_LOCAL, where CHOLMOD's calls reach the BLAS directly).
long smallBlasCallCount();

}  // namespace ablmg::fem
