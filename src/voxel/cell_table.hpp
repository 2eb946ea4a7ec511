#pragma once
// An open-addressing table from a cell key to the cell's number, numbered
// in the order the keys are first met: the grouping step of downsampling,
// plane extraction and the bird's-eye search's columns, where a standard
// node-based map would spend its time allocating.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace detail {

inline std::uint64_t mix(std::uint64_t h) {
  // Finalizer of MurmurHash3: spreads every input bit over the low bits the
  // power-of-two table uses.
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  return h ^ (h >> 33);
}

inline std::uint64_t hashOf(std::uint64_t packed) { return mix(packed); }
inline std::uint64_t hashOf(const VoxelKey& key) {
  return mix(static_cast<std::uint64_t>(key.x) ^
             mix(static_cast<std::uint64_t>(key.y) ^ mix(static_cast<std::uint64_t>(key.z))));
}

}  // namespace detail

// Open-addressing table from cell key to cell number. It starts small and
// doubles at half load: clouds range from one cell per point (fine scan
// voxels) to thousands of points per cell (4 m plane voxels), and a table
// sized for the worst case would spend its time on page faults.
template <typename Key>
class CellTable {
 public:
  // Room for `cells` before the first doubling.
  explicit CellTable(std::size_t cells) {
    std::size_t capacity = kMinCapacity;
    while (capacity < 2 * cells) capacity *= 2;
    slots_.resize(capacity);
  }

  // Starts loading the slot of a key needed soon: a large table misses the
  // caches, and hiding that miss is most of the speed.
  void prefetch(const Key& key) const { __builtin_prefetch(&slots_[slotOf(key)]); }

  // The cell number of `key`, or `next` (recorded) if the key is new.
  std::uint32_t find(const Key& key, std::uint32_t next) {
    Slot& slot = probe(key);
    if (slot.cell != kEmpty) return slot.cell;
    slot = {key, next};
    if (2 * ++used_ > slots_.size()) grow();
    return next;
  }

 private:
  static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  static constexpr std::size_t kMinCapacity = 1024;
  struct Slot {  // key and cell side by side: one cache line per probe
    Key key{};
    std::uint32_t cell = kEmpty;
  };

  std::size_t slotOf(const Key& key) const { return detail::hashOf(key) & (slots_.size() - 1); }

  // The slot holding `key`, or the empty slot where it belongs.
  Slot& probe(const Key& key) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = slotOf(key);; i = (i + 1) & mask) {
      Slot& slot = slots_[i];
      if (slot.cell == kEmpty || slot.key == key) return slot;
    }
  }

  void grow() {
    std::vector<Slot> old(2 * slots_.size());
    old.swap(slots_);
    for (const Slot& slot : old) {
      if (slot.cell != kEmpty) probe(slot.key) = slot;
    }
  }

  std::vector<Slot> slots_;
  std::size_t used_ = 0;
};

}  // namespace hba::voxel
