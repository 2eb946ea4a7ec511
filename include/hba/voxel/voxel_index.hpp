#pragma once
// Numbers the distinct voxel keys in the order they are first seen: an
// open-addressing table (linear probing, grown by doubling at half load),
// flat in memory. For maps that grow scan by scan, where a node-based hash
// map spends its time in allocation and cache misses.
#include <cstdint>
#include <vector>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {

class VoxelIndex {
 public:
  // The number of `key`: an existing one, or size() before the call (then
  // `inserted` is set).
  std::uint32_t insert(const VoxelKey& key, bool& inserted) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    std::size_t s = home(key);
    while (slots_[s].number != kEmpty) {
      if (slots_[s].key == key) {
        inserted = false;
        return slots_[s].number;
      }
      s = (s + 1) & mask_;
    }
    slots_[s] = {key, static_cast<std::uint32_t>(count_)};
    inserted = true;
    return static_cast<std::uint32_t>(count_++);
  }

  // The number of `key`, or -1 when it was never inserted.
  std::int64_t find(const VoxelKey& key) const {
    if (slots_.empty()) return -1;
    for (std::size_t s = home(key); slots_[s].number != kEmpty; s = (s + 1) & mask_) {
      if (slots_[s].key == key) return slots_[s].number;
    }
    return -1;
  }

  std::size_t size() const { return count_; }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  struct Slot {
    VoxelKey key;
    std::uint32_t number = kEmpty;
  };

  std::size_t home(const VoxelKey& key) const {
    // Fibonacci hashing spreads the low-quality key hash over the table.
    const std::uint64_t h = static_cast<std::uint64_t>(VoxelKeyHash{}(key)) * 0x9E3779B97F4A7C15ULL;
    return static_cast<std::size_t>(h >> 20) & mask_;
  }

  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? 1024 : 2 * old.size(), Slot{});
    mask_ = slots_.size() - 1;
    for (const Slot& slot : old) {
      if (slot.number == kEmpty) continue;
      std::size_t s = home(slot.key);
      while (slots_[s].number != kEmpty) s = (s + 1) & mask_;
      slots_[s] = slot;
    }
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::size_t count_ = 0;
};

}  // namespace hba::voxel
