// A priority queue on a flat array with four children per node (a 4-ary heap; D. B. Johnson, "Priority
// queues with update and finding minimum spanning trees", 1975; LaMarca & Ladner, "The influence of caches
// on the performance of heaps", 1996): half the levels of a binary heap, and a node's children share a
// cache line. The decimation's collapse queue (photogrammetry/mesh/mesh_decimate_qem.cc) spends most of
// its time sifting down; the figures are in bench/RESULTS.md.
//
// `Before(x, y)`: x leaves the queue first. Under a strict total order the sequence of pops is fixed
// whatever the heap's shape, so it is the same as any other exact priority queue's (std::priority_queue
// included): swapping one for the other keeps a program's output.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace cinepath::photogrammetry {

template <typename T, typename Before>
class QuaternaryHeap {
 public:
  explicit QuaternaryHeap(Before before = Before()) : before_(before) {}

  bool empty() const { return items_.empty(); }
  size_t size() const { return items_.size(); }
  void reserve(size_t n) { items_.reserve(n); }
  void clear() { items_.clear(); }
  // The items in heap order (not sorted).
  const std::vector<T>& items() const { return items_; }

  // Adds an item without restoring the heap: call Heapify before the next Push or Pop.
  void PushUnordered(const T& item) { items_.push_back(item); }
  // Restores the heap over all items (bottom-up, O(n)).
  void Heapify() {
    if (items_.size() < 2) return;
    for (size_t i = (items_.size() - 2) / kArity + 1; i-- > 0;) SiftDown(i, items_[i]);
  }

  void Push(const T& item) {
    size_t i = items_.size();
    items_.push_back(item);
    while (i > 0) {
      const size_t parent = (i - 1) / kArity;
      if (!before_(item, items_[parent])) break;
      items_[i] = items_[parent];
      i = parent;
    }
    items_[i] = item;
  }

  // Removes and returns the first item. The heap must not be empty. The hole left at the top goes down
  // to a leaf along the first children, then the last item climbs back from there ("bottom-up", as in
  // Wegener's heapsort): the last item belongs near the bottom, so this skips the comparison with it
  // on every level down.
  T Pop() {
    T top = std::move(items_.front());
    T last = std::move(items_.back());
    items_.pop_back();
    const size_t n = items_.size();
    if (n == 0) return top;
    size_t i = 0;
    for (;;) {
      const size_t first = kArity * i + 1;
      if (first >= n) break;
      const size_t best = FirstChild(first, n);
      items_[i] = std::move(items_[best]);
      i = best;
    }
    while (i > 0) {
      const size_t parent = (i - 1) / kArity;
      if (!before_(last, items_[parent])) break;
      items_[i] = std::move(items_[parent]);
      i = parent;
    }
    items_[i] = std::move(last);
    return top;
  }

 private:
  static constexpr size_t kArity = 4;

  // The first of the children first .. first + 3 (those below n), chosen without branches on the items
  // (their order is a coin toss to the branch predictor): a tournament of pairs when all four exist.
  size_t FirstChild(size_t first, size_t n) const {
    if (first + kArity <= n) {
      const size_t a = before_(items_[first + 1], items_[first]) ? first + 1 : first;
      const size_t b = before_(items_[first + 3], items_[first + 2]) ? first + 3 : first + 2;
      return before_(items_[b], items_[a]) ? b : a;
    }
    size_t best = first;
    for (size_t c = first + 1; c < n; ++c) best = before_(items_[c], items_[best]) ? c : best;
    return best;
  }

  // Places `item` at the hole i or below it.
  void SiftDown(size_t i, T item) {
    const size_t n = items_.size();
    for (;;) {
      const size_t first = kArity * i + 1;
      if (first >= n) break;
      const size_t best = FirstChild(first, n);
      if (!before_(items_[best], item)) break;
      items_[i] = std::move(items_[best]);
      i = best;
    }
    items_[i] = std::move(item);
  }

  std::vector<T> items_;
  Before before_;
};

}  // namespace cinepath::photogrammetry
