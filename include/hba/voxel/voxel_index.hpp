#pragma once
// Numbers the distinct keys in the order they are first seen: an
// open-addressing table (linear probing, grown by doubling at 70 % load),
// flat in memory. For maps that grow scan by scan, where a node-based hash
// map spends its time in allocation and cache misses.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {

template <typename Key, typename Hash>
class FlatIndex {
 public:
  // The number of `key`: an existing one, or size() before the call (then
  // `inserted` is set).
  std::uint32_t insert(const Key& key, bool& inserted) {
    if (10 * (count_ + 1) > 7 * slots_.size()) grow();
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

  std::size_t size() const { return count_; }

  // Starts loading the slot where `key` is looked for first: a large index
  // misses the caches, and hiding that miss is most of an insert's cost.
  void prefetch(const Key& key) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(key)]);
  }

  // Forgets every key and keeps the table: refilled to a similar size, it
  // neither grows nor touches fresh memory again.
  void clear() {
    std::fill(slots_.begin(), slots_.end(), Slot{});
    count_ = 0;
  }

  // Room for `keys` keys without growing.
  void reserve(std::size_t keys) {
    while (10 * keys > 7 * slots_.size()) grow();
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  struct Slot {
    Key key{};
    std::uint32_t number = kEmpty;
  };

  std::size_t home(const Key& key) const {
    // Fibonacci hashing spreads a low-quality hash over the table.
    const std::uint64_t h = static_cast<std::uint64_t>(Hash{}(key)) * 0x9E3779B97F4A7C15ULL;
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

// Voxel keys as they are (24 bytes): any coordinates.
using VoxelIndex = FlatIndex<VoxelKey, VoxelKeyHash>;

// Keys packed into 64 bits by the caller (16-byte slots): for the many
// voxels of a picture.
struct PackedKeyHash {
  // MurmurHash3's finalizer: every key bit reaches the bits the table uses.
  // The key itself hashed only its low (x) bits well: voxels stacked in z
  // shared a home and probed long runs (the picture's index spent half its
  // time there).
  std::size_t operator()(std::uint64_t key) const {
    key ^= key >> 33;
    key *= 0xff51afd7ed558ccdULL;
    key ^= key >> 33;
    key *= 0xc4ceb9fe1a85ec53ULL;
    return static_cast<std::size_t>(key ^ (key >> 33));
  }
};
using PackedVoxelIndex = FlatIndex<std::uint64_t, PackedKeyHash>;

// Which packed keys were seen, in 8-byte slots: half a PackedVoxelIndex's
// memory, so twice as many voxels stay in the caches (a picture's points
// need no numbers). Grown by doubling at 70 % load.
class PackedVoxelSet {
 public:
  // Whether `key` is new (and now recorded).
  bool insert(std::uint64_t key) {
    if (key == kEmpty) {  // the empty slots' mark, kept aside
      const bool fresh = !has_empty_key_;
      has_empty_key_ = true;
      count_ += fresh;
      return fresh;
    }
    if (10 * (stored_ + 1) > 7 * slots_.size()) grow();
    std::size_t s = home(key);
    while (slots_[s] != kEmpty) {
      if (slots_[s] == key) return false;
      s = (s + 1) & mask_;
    }
    slots_[s] = key;
    ++stored_;
    ++count_;
    return true;
  }

  std::size_t size() const { return count_; }

  // Starts loading the slot where `key` is looked for first.
  void prefetch(std::uint64_t key) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(key)]);
  }

  // Room for `keys` keys without growing.
  void reserve(std::size_t keys) {
    while (10 * keys > 7 * slots_.size()) grow();
  }

  // Forgets every key and keeps the table (no fresh memory to fault in).
  void clear() {
    std::fill(slots_.begin(), slots_.end(), kEmpty);
    stored_ = count_ = 0;
    has_empty_key_ = false;
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  std::size_t home(std::uint64_t key) const {
    const std::uint64_t hash = PackedKeyHash{}(key);
    return static_cast<std::size_t>((hash * 0x9E3779B97F4A7C15ULL) >> 20) & mask_;
  }

  void grow() {
    std::vector<std::uint64_t> old = std::move(slots_);
    slots_.assign(old.empty() ? 1024 : 2 * old.size(), kEmpty);
    mask_ = slots_.size() - 1;
    for (const std::uint64_t key : old) {
      if (key == kEmpty) continue;
      std::size_t s = home(key);
      while (slots_[s] != kEmpty) s = (s + 1) & mask_;
      slots_[s] = key;
    }
  }

  std::vector<std::uint64_t> slots_;
  std::size_t mask_ = 0;
  std::size_t stored_ = 0;  // in slots_
  std::size_t count_ = 0;   // stored_, and the empty mark's key if seen
  bool has_empty_key_ = false;
};

}  // namespace hba::voxel
