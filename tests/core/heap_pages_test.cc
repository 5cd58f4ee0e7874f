#include "core/heap_pages.h"

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace cinepath {
namespace {

// The VmFlags line of /proc/self/smaps for the mapping that holds `address` ("" if none).
std::string VmFlagsAt(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const uintptr_t a = reinterpret_cast<uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-' && line.find(':') > line.find(' ')) {
      inside = lo <= a && a < hi;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return "";
}

// The main thread's large buffers after the preparation come from the heap's range asked for in huge
// pages (not from an mmap of their own in 4 KiB pages), and the kernel has marked that range ("hg").
TEST(HeapPages, LargeBuffersComeFromTheRangeAskedForInHugePages) {
  const HeapPreparation done = PrepareHeapForLargeBuffers(size_t(64) << 20);
  if (done.advised_bytes == 0) GTEST_SKIP() << "no glibc heap or no madvise(MADV_HUGEPAGE) here";
  EXPECT_EQ(reinterpret_cast<uintptr_t>(done.advised_begin) % (uintptr_t(2) << 20), 0u);
  EXPECT_GE(done.advised_bytes, size_t(60) << 20);
  EXPECT_NE(VmFlagsAt(done.advised_begin).find(" hg"), std::string::npos) << VmFlagsAt(done.advised_begin);

  // 12 MB, as one frame's largest buffers at 1920 px: below the 32 MiB threshold, so from the heap.
  std::vector<double> buffer(size_t(1) << 20 | size_t(1) << 19);
  const auto begin = reinterpret_cast<uintptr_t>(done.advised_begin);
  const auto at = reinterpret_cast<uintptr_t>(buffer.data());
  EXPECT_LT(at, begin + done.advised_bytes);
  EXPECT_GT(at + buffer.size() * sizeof(double), begin);
  // Freed and asked for again: the same memory (the heap's top is not given back to the kernel).
  const double* first = buffer.data();
  std::vector<double>().swap(buffer);
  std::vector<double> again(size_t(1) << 20 | size_t(1) << 19);
  EXPECT_EQ(again.data(), first);
}

}  // namespace
}  // namespace cinepath
