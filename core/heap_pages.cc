#include "core/heap_pages.h"

#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace cinepath {

HeapPreparation PrepareHeapForLargeBuffers(size_t reserve_bytes) {
  HeapPreparation done;
#if defined(__GLIBC__) && defined(MADV_HUGEPAGE)
  constexpr uintptr_t kHugePage = uintptr_t(2) << 20;
  // 32 MiB is glibc's largest mmap threshold on 64-bit; larger allocations (an 8192² atlas) stay mmaps.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, int(reserve_bytes));
  // The heap's free top, [end - keepcost, end), is where the next allocations of the main thread go.
  // When it is smaller than the reserve, one allocation larger than it makes malloc extend the heap (by
  // the allocation plus the top pad); freed at once, all of it is free top again, untouched.
  if (const size_t top = mallinfo2().keepcost; top < reserve_bytes && top + 4096 < (32u << 20)) {
    void* volatile grow = std::malloc(top + 4096);  // volatile: the compiler may not drop the pair
    std::free(grow);
  }
  // Later growth in 32 MiB steps, not glibc's default 128 KiB: fewer brk calls (a large mesh's arrays).
  mallopt(M_TOP_PAD, 32 << 20);
  const uintptr_t end = reinterpret_cast<uintptr_t>(sbrk(0)), top = mallinfo2().keepcost;
  if (end == uintptr_t(-1) || top > end) return done;
  // The top chunk's first page holds its header (touched already): 2 MiB pages from the next boundary.
  const uintptr_t begin = (end - top + 4096 + kHugePage - 1) & ~(kHugePage - 1), stop = end & ~(kHugePage - 1);
  if (stop > begin && madvise(reinterpret_cast<void*>(begin), stop - begin, MADV_HUGEPAGE) == 0) {
    done.advised_begin = reinterpret_cast<void*>(begin);
    done.advised_bytes = stop - begin;
  }
#else
  (void)reserve_bytes;
#endif
  return done;
}

}  // namespace cinepath
