// The ablmg program's global operator new: every block of 4 MB or more is offered to the kernel
// for transparent huge pages before it is first written.
//
// Where transparent huge pages are enabled for advised memory only (Debian's default,
// /sys/kernel/mm/transparent_hugepage/enabled = madvise), each 4 KB page of a fresh array costs
// one page fault at its first write; advised, each 2 MB costs one. On a virtual machine whose
// faults cost ≈ 6 µs that is a third of the meshing time of a 10⁶-triangle remesh (1.5·10⁵
// faults; docs/experiments.md, "Transparent huge pages"). The blocks are glibc's as before
// (malloc and free, so every operator delete stays free), and the results do not depend on it.
// Only programs do this (ablmg, and the benchmarks, which measure what ablmg does): a library must
// not replace the global operator new, so programs that link libablmg choose their own policy
// (glibc's GLIBC_TUNABLES=glibc.malloc.hugetlb=1 does the same for every malloc; docs/library.md).
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kLargeBlockBytes = std::size_t(4) << 20;

/// MADV_HUGEPAGE on the pages of [block, block + bytes). glibc maps a large block on its own,
/// 16 bytes past the mapping's start, and the kernel starts mappings of 2 MB or more on a 2 MB
/// boundary, so the first page of the block begins a huge page. A hint: a kernel without
/// transparent huge pages refuses it, and nothing changes.
void adviseHugePages(void* block, std::size_t bytes) {
  const auto first = reinterpret_cast<std::uintptr_t>(block);
  static const auto pageBytes = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = first & ~(pageBytes - 1);
  madvise(reinterpret_cast<void*>(begin), first + bytes - begin, MADV_HUGEPAGE);
}

}  // namespace

// The other forms of new (array, nothrow) call this one; the aligned forms keep their own pair.
void* operator new(std::size_t bytes) {
  for (;;) {
    if (void* block = std::malloc(bytes == 0 ? 1 : bytes)) {
      if (bytes >= kLargeBlockBytes) adviseHugePages(block, bytes);
      return block;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void operator delete(void* block) noexcept { std::free(block); }
void operator delete(void* block, std::size_t) noexcept { std::free(block); }
