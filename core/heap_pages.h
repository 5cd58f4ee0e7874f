// The heap of a command that allocates large short-lived buffers (render's per-frame images) laid out so
// that touching them costs few page faults. Each first touch of a 4 KiB page traps into the kernel; on a
// virtual machine a trap costs microseconds, and one frame of the bundled scene touched ~9,000 pages.
#pragma once

#include <cstddef>

namespace cinepath {

// What PrepareHeapForLargeBuffers did (for -v and tests).
struct HeapPreparation {
  void* advised_begin = nullptr;  // the heap's range asked for in 2 MiB pages, 2 MiB-aligned
  size_t advised_bytes = 0;       // its size (0: not available here, e.g. under a sanitizer's allocator)
};

// Call once, early, on the main thread, before the large allocations and before other threads allocate.
// It:
//  - keeps allocations below 32 MiB in malloc's heap rather than in a fresh mmap each (glibc returns
//    those to the kernel on free, so the next frame's buffers fault their pages in again), never trims
//    the heap's top (a freed frame's buffers serve the next one), and grows it in 32 MiB steps;
//  - puts every thread in the one main arena, so that the loading threads' buffers share that heap;
//  - grows the main heap by `reserve_bytes` at once (address space only: pages come when touched) and
//    asks the kernel for transparent huge pages over it (madvise, which Debian's "madvise" mode honours):
//    buffers there come in 2 MiB pages, one fault each instead of 512.
// Only hints: where glibc or the kernel lacks them, nothing changes. Never changes what is computed.
HeapPreparation PrepareHeapForLargeBuffers(size_t reserve_bytes);

}  // namespace cinepath
