// INTERNAL to surface_poisson.cc: the order in which CGAL's Poisson reconstruction visits its
// triangulations' vertices and cells, made independent of where the allocator put them.
//
// CGAL compares triangulation handles by address unless the vertex or cell type carries a time stamp
// (CGAL::Time_stamper): the Poisson solver's refinement and the surface mesher keep std::set and
// std::map of handles and walk them in that order. The Poisson reconstruction's own vertex and cell
// types carry no stamp, and the address of a Compact_container block depends on the heap's history: the
// blocks that other threads freed earlier in the process, and so the scheduling of every parallel step
// before. Measured: the same points and seed gave 4,550 or 4,543 faces from one process to the next; six
// different heap histories in one test program gave five different surfaces.
//
// Two remedies, both making handles compare in creation order, which depends on the input alone:
// - The surface mesher's triangulation is ours to choose (PoissonMesherTriangulation): its vertex and
//   cell types carry a stamp (WithCreationStamp), which CGAL's Compact_container sets on creation and
//   compares.
// - The solver's triangulation is fixed inside CGAL::Poisson_reconstruction_function. For its vertex and
//   cell types, CGAL::Get_time_stamper is specialised to BlockOrderStamper, a time-stamp policy that
//   keeps the order outside the elements: a Compact_container calls initialize_time_stamp on every slot
//   of each new block, so the policy knows every block and the order they were allocated in, and a
//   handle's place is (its block's allocation order, its slot in the block).
// Include this header before anything instantiates the solver's types (first in the .cc after the CGAL
// headers), and hold a CreationOrderScope around each reconstruction.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <type_traits>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Poisson_reconstruction_function.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/Time_stamper.h>
#include <CGAL/tags.h>

namespace cinepath::photogrammetry::internal {

// The blocks of one element type's containers, in the order they were allocated. CGAL's
// Compact_container calls initialize_time_stamp on every slot of a new block, from the last slot down
// to the first, and on nothing else; a run of such calls on adjacent, descending addresses is one
// block. A block that reuses memory of a freed block replaces that block's record.
class BlockOrder {
 public:
  void AddSlot(std::uintptr_t slot, std::size_t slot_size) {
    const bool continues = current_ < blocks_.size() && slot + slot_size == blocks_[current_].first;
    // Records of freed blocks that covered this address are stale.
    for (std::size_t i = Containing(slot); i < blocks_.size() && !(continues && i == current_); i = Containing(slot)) {
      blocks_.erase(blocks_.begin() + static_cast<std::ptrdiff_t>(i));
      if (current_ < blocks_.size() && i < current_) --current_;
    }
    if (continues) {
      blocks_[current_].first = slot;
      return;
    }
    const auto at = std::upper_bound(blocks_.begin(), blocks_.end(), slot,
                                     [](std::uintptr_t a, const Block& b) { return a < b.first; });
    current_ = static_cast<std::size_t>(at - blocks_.begin());
    blocks_.insert(at, Block{slot, slot, next_block_++});
  }
  // (allocation order of its block) × 2^32 + (its slot in the block); -1 outside every block.
  std::size_t Stamp(std::uintptr_t address, std::size_t slot_size) const {
    const std::size_t i = Containing(address);
    if (i == blocks_.size()) return static_cast<std::size_t>(-1);
    return (blocks_[i].index << 32) | ((address - blocks_[i].first) / slot_size);
  }
  void Clear() {
    std::vector<Block>().swap(blocks_);
    current_ = static_cast<std::size_t>(-1);
    next_block_ = 0;
  }

 private:
  struct Block {
    std::uintptr_t first, last;  // the first and last slot's addresses
    std::size_t index;
  };
  std::size_t Containing(std::uintptr_t address) const {  // blocks_.size() if none
    auto it = std::upper_bound(blocks_.begin(), blocks_.end(), address,
                               [](std::uintptr_t a, const Block& b) { return a < b.first; });
    if (it == blocks_.begin()) return blocks_.size();
    --it;
    return address <= it->last ? static_cast<std::size_t>(it - blocks_.begin()) : blocks_.size();
  }
  std::vector<Block> blocks_;  // by address
  std::size_t current_ = static_cast<std::size_t>(-1), next_block_ = 0;
};

// CGAL's time-stamp policy interface (see CGAL/Time_stamper.h), ordering elements by (block allocation
// order, slot within the block).
template <typename T>
struct BlockOrderStamper {
  static BlockOrder& Blocks() {
    static BlockOrder blocks;  // guarded by CreationOrderScope's lock
    return blocks;
  }
  static void initialize_time_stamp(T* p) { Blocks().AddSlot(reinterpret_cast<std::uintptr_t>(p), sizeof(T)); }
  template <typename Counter>
  static void set_time_stamp(T*, Counter&) {}
  static std::size_t time_stamp(const T* p) {
    return p == nullptr ? static_cast<std::size_t>(-1) : Blocks().Stamp(reinterpret_cast<std::uintptr_t>(p), sizeof(T));
  }
  static std::size_t hash_value(const T* p) { return time_stamp(p); }
  static bool less(const T* a, const T* b) {
    if (a == nullptr) return b != nullptr;
    if (b == nullptr || a == b) return false;
    return time_stamp(a) < time_stamp(b);
  }
};

// A vertex or cell base with a creation stamp, in CGAL's time-stamp interface.
template <typename Base>
class WithCreationStamp : public Base {
 public:
  using Has_timestamp = CGAL::Tag_true;
  template <typename Tds>
  struct Rebind_TDS {
    using Other = WithCreationStamp<typename Base::template Rebind_TDS<Tds>::Other>;
  };
  using Base::Base;
  std::size_t time_stamp() const { return time_stamp_; }
  void set_time_stamp(std::size_t stamp) { time_stamp_ = stamp; }

 private:
  std::size_t time_stamp_ = static_cast<std::size_t>(-1);
};

using PoissonKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// The surface mesher's triangulation: CGAL's default for the surface mesher (as in
// CGAL::poisson_surface_reconstruction_delaunay), with stamped vertices and cells.
using PoissonMesherTraits = CGAL::Robust_circumcenter_traits_3<PoissonKernel>;
using PoissonMesherTriangulation =
    CGAL::Delaunay_triangulation_3<PoissonMesherTraits,
                                   CGAL::Triangulation_data_structure_3<
                                       WithCreationStamp<CGAL::Surface_mesh_vertex_base_3<PoissonMesherTraits>>,
                                       WithCreationStamp<CGAL::Delaunay_triangulation_cell_base_with_circumcenter_3<
                                           PoissonMesherTraits, CGAL::Surface_mesh_cell_base_3<PoissonMesherTraits>>>>>;

// The triangulation data structure of CGAL::Poisson_reconstruction_function<PoissonKernel> (the
// solver's Delaunay refinement), spelled as CGAL spells it; the static_assert below checks it.
using PoissonSolverTraits = CGAL::Reconstruction_triangulation_default_geom_traits_3<
    CGAL::Robust_circumcenter_filtered_traits_3<PoissonKernel>>;
using PoissonSolverTds = CGAL::Triangulation_data_structure_3<
    CGAL::Reconstruction_vertex_base_3<PoissonSolverTraits>,
    CGAL::Delaunay_triangulation_cell_base_3<PoissonSolverTraits,
                                             CGAL::Triangulation_cell_base_with_info_3<int, PoissonSolverTraits>>>;

// One reconstruction at a time in the process: holds the lock, and forgets the blocks on entry and
// on exit.
class CreationOrderScope {
 public:
  CreationOrderScope() : lock_(Mutex()) { Clear(); }
  ~CreationOrderScope() { Clear(); }
  CreationOrderScope(const CreationOrderScope&) = delete;
  CreationOrderScope& operator=(const CreationOrderScope&) = delete;

 private:
  static void Clear() {
    BlockOrderStamper<PoissonSolverTds::Vertex>::Blocks().Clear();
    BlockOrderStamper<PoissonSolverTds::Cell>::Blocks().Clear();
  }
  static std::mutex& Mutex() {
    static std::mutex mutex;
    return mutex;
  }
  std::lock_guard<std::mutex> lock_;
};

}  // namespace cinepath::photogrammetry::internal

namespace CGAL {
template <>
struct Get_time_stamper<cinepath::photogrammetry::internal::PoissonSolverTds::Vertex, false> {
  using type = cinepath::photogrammetry::internal::BlockOrderStamper<
      cinepath::photogrammetry::internal::PoissonSolverTds::Vertex>;
};
template <>
struct Get_time_stamper<cinepath::photogrammetry::internal::PoissonSolverTds::Cell, false> {
  using type =
      cinepath::photogrammetry::internal::BlockOrderStamper<cinepath::photogrammetry::internal::PoissonSolverTds::Cell>;
};
}  // namespace CGAL

static_assert(std::is_same_v<cinepath::photogrammetry::internal::PoissonSolverTds,
                             CGAL::Poisson_reconstruction_function<cinepath::photogrammetry::internal::PoissonKernel>::
                                 Triangulation::Triangulation_data_structure>);
static_assert(std::is_base_of_v<cinepath::photogrammetry::internal::BlockOrderStamper<
                                    cinepath::photogrammetry::internal::PoissonSolverTds::Cell>,
                                CGAL::Time_stamper_impl<cinepath::photogrammetry::internal::PoissonSolverTds::Cell>>);
static_assert(
    std::is_base_of_v<CGAL::Time_stamper<cinepath::photogrammetry::internal::PoissonMesherTriangulation::Vertex>,
                      CGAL::Time_stamper_impl<cinepath::photogrammetry::internal::PoissonMesherTriangulation::Vertex>>);
