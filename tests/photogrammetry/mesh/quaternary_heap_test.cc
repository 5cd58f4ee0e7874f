#include "photogrammetry/mesh/quaternary_heap.h"

#include <algorithm>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace cinepath::photogrammetry {
namespace {

using MinHeap = QuaternaryHeap<int, std::less<int>>;

std::vector<int> PopAll(MinHeap& heap) {
  std::vector<int> out;
  while (!heap.empty()) out.push_back(heap.Pop());
  return out;
}

// Every size from 0 to 70 (partial last levels of every shape), with repeated values: the pops come
// out sorted, built by Push or by PushUnordered + Heapify.
TEST(QuaternaryHeap, PopsInOrderAtEverySize) {
  std::mt19937 rng(7);
  for (int n = 0; n <= 70; ++n) {
    std::vector<int> values(n);
    for (int& v : values) v = static_cast<int>(rng() % 20);
    std::vector<int> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    MinHeap pushed, heapified;
    for (int v : values) pushed.Push(v);
    for (int v : values) heapified.PushUnordered(v);
    heapified.Heapify();
    EXPECT_EQ(PopAll(pushed), sorted) << n;
    EXPECT_EQ(PopAll(heapified), sorted) << n;
  }
}

// Pops and pushes interleaved as the decimation uses them (a pop, then a few pushes, some of them
// cheaper than what is left), against std::priority_queue under the same order.
TEST(QuaternaryHeap, InterleavedPushesAndPopsMatchTheStandardQueue) {
  std::mt19937 rng(11);
  MinHeap heap;
  std::vector<int> reference;  // a min-heap by std::greater
  for (int i = 0; i < 5000; ++i) {
    const int v = static_cast<int>(rng() % 100000);
    heap.PushUnordered(v);
    reference.push_back(v);
  }
  heap.Heapify();
  std::make_heap(reference.begin(), reference.end(), std::greater<int>());
  int popped = 0;
  while (!heap.empty()) {
    ASSERT_EQ(heap.size(), reference.size());
    const int top = heap.Pop();
    std::pop_heap(reference.begin(), reference.end(), std::greater<int>());
    ASSERT_EQ(top, reference.back()) << popped;
    reference.pop_back();
    ++popped;
    if (popped < 20000) {
      for (unsigned k = rng() % 4; k-- > 0;) {
        const int v = top + static_cast<int>(rng() % 1000) - 100;
        heap.Push(v);
        reference.push_back(v);
        std::push_heap(reference.begin(), reference.end(), std::greater<int>());
      }
    }
  }
  EXPECT_TRUE(reference.empty());
  EXPECT_GT(popped, 5000);
}

// The order is the comparator's: a max-heap by std::greater.
TEST(QuaternaryHeap, FollowsTheComparator) {
  QuaternaryHeap<int, std::greater<int>> heap;
  for (int v : {3, 9, 1, 7, 5}) heap.Push(v);
  std::vector<int> out;
  while (!heap.empty()) out.push_back(heap.Pop());
  EXPECT_EQ(out, (std::vector<int>{9, 7, 5, 3, 1}));
}

}  // namespace
}  // namespace cinepath::photogrammetry
