// The heap of a command that allocates large short-lived buffers (render's per-frame images, optimize's
// problem of tens of thousands of small cost objects, built again for each stage of its ladder, mesh's
// arrays over every face and vertex) laid out so that touching them costs few page faults. Each first touch of a 4 KiB
// page traps into the kernel; on a virtual machine a trap costs microseconds, and one frame of the bundled scene
// touched ~9,000 pages.
#pragma once

#include <cstddef>

namespace cinepath {

// What PrepareHeapForLargeBuffers did (for -v and tests).
struct HeapPreparation {
  void* advised_begin = nullptr;  // the heap's range asked for in 2 MiB pages, 2 MiB-aligned
  size_t advised_bytes = 0;       // its size (0: not available here, e.g. under a sanitizer's allocator)
};

// Call once, early, on the main thread, before the large allocations. It:
//  - keeps allocations below 32 MiB in malloc's heaps rather than in a fresh mmap each (glibc returns
//    those to the kernel on free, so the next frame's buffers fault their pages in again), never trims
//    the heap's top (a freed frame's buffers serve the next one), and grows it in 32 MiB steps;
//  - grows the main heap by `reserve_bytes` at once (address space only: pages come when touched) and
//    asks the kernel for transparent huge pages over it (madvise, which Debian's "madvise" mode honours):
//    the main thread's buffers there come in 2 MiB pages, one fault each instead of 512.
// The other threads keep their own arenas (in 4 KiB pages): one arena for all, tried, cut the faults
// further (~1,000 against ~3,200 for a bundled frame) but its system time varied more and a 1 M-face
// scene's BVH build, allocating on both threads, took twice as long.
// Only hints: where glibc or the kernel lacks them, nothing changes. Never changes what is computed.
HeapPreparation PrepareHeapForLargeBuffers(size_t reserve_bytes);

// The reserve the commands pass (render, optimize, mesh): address space, not memory.
constexpr size_t kCommandHeapReserveBytes = size_t(128) << 20;

}  // namespace cinepath
