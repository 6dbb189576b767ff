#include "ablmg/fem/cholmod_threads.hpp"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>

namespace ablmg::fem {
namespace {

thread_local int scopeDepth = 0;        // CholmodScopes alive on this thread
thread_local long teamlessRegions = 0;  // regions run without a team on this thread

}  // namespace

CholmodScope::CholmodScope() : saved_(omp_get_max_active_levels()) {
  omp_set_max_active_levels(0);
  ++scopeDepth;
}

CholmodScope::~CholmodScope() {
  --scopeDepth;
  omp_set_max_active_levels(saved_);
}

long teamlessRegionCount() { return teamlessRegions; }

}  // namespace ablmg::fem

/// libgomp's entry point for `#pragma omp parallel` (GCC's code, CHOLMOD's included, calls
/// it with the outlined body `fn`, its argument, the requested thread count and the
/// proc_bind flags). Defined here, it takes the calls of every library that the dynamic
/// linker resolves to this program (libcholmod.so among them): inside a CholmodScope on a
/// thread in no parallel region, the region's team would be one thread (max-active-levels
/// 0), and the body runs directly on the calling thread; every other call goes to the
/// runtime's own GOMP_parallel (the next definition in the lookup order: libgomp's, or
/// LLVM's libomp's compatible one). fem/cholmod_threads.hpp says why.
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned numThreads, unsigned flags) {
  using Entry = void (*)(void (*)(void*), void*, unsigned, unsigned);
  if (ablmg::fem::scopeDepth > 0 && omp_get_level() == 0) {
    ++ablmg::fem::teamlessRegions;
    fn(data);
    return;
  }
  static const Entry runtime = reinterpret_cast<Entry>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  if (!runtime) {
    std::fputs("ablmg: the OpenMP runtime's GOMP_parallel was not found (fem/cholmod_threads.cpp)\n", stderr);
    std::abort();
  }
  runtime(fn, data, numThreads, flags);
}
