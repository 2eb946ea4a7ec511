#pragma once
// The one hash table of hba: keys numbered in the order they are first met
// (KeyNumbers), or only recorded (PackedKeySet). Open addressing with
// linear probing, flat in memory, doubled at half load, for the grouping
// steps (scan downsampling, plane extraction, a merged map's voxels, a
// picture's points) where a node-based map spends its time allocating and
// missing the caches.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {

// MurmurHash3's finalizer: every bit of `h` reaches every bit of the
// result, in particular the low bits a power-of-two table uses (a packed
// key's low bits hold one coordinate: unmixed, cells that differ only in
// the others would share a home and probe long runs).
inline std::uint64_t mixBits(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  return h ^ (h >> 33);
}

namespace detail {

inline std::uint64_t hashOf(std::uint64_t packed) { return mixBits(packed); }
inline std::uint64_t hashOf(const VoxelKey& key) {
  return mixBits(static_cast<std::uint64_t>(key.x) ^
                 mixBits(static_cast<std::uint64_t>(key.y) ^ mixBits(static_cast<std::uint64_t>(key.z))));
}

// Probing and growth over a slot that holds a key and knows when it is
// empty (Slot{} is). Half load at most: clouds range from one cell per
// point to thousands of points per cell, and most lookups of a fresh cloud
// are of keys not yet there, which a fuller table makes long.
template <typename Key, typename Slot>
class OpenTable {
 public:
  // Room for `keys` keys without growing (allocated at once: a table
  // sized for a cloud is megabytes).
  void reserve(std::size_t keys) {
    std::size_t capacity = std::max(slots_.size(), kMinCapacity);
    while (2 * keys > capacity) capacity *= 2;
    if (capacity > slots_.size()) rehash(capacity);
  }

  // Starts loading the slot where `key` is looked for first: a large table
  // misses the caches, and hiding that miss is most of a lookup's cost.
  void prefetch(const Key& key) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(key)]);
  }

  // Forgets every key and keeps the table: refilled to a similar size, it
  // neither grows nor touches fresh memory again.
  void clear() {
    std::fill(slots_.begin(), slots_.end(), Slot{});
    stored_ = 0;
  }

 protected:
  // The slot holding `key`, or the empty slot where it belongs, with room
  // for one key more.
  Slot& slotFor(const Key& key) {
    if (2 * (stored_ + 1) > slots_.size()) rehash(slots_.empty() ? kMinCapacity : 2 * slots_.size());
    std::size_t s = home(key);
    while (!slots_[s].empty() && !(slots_[s].key == key)) s = (s + 1) & mask_;
    return slots_[s];
  }

  std::size_t stored_ = 0;  // keys in slots_

 private:
  static constexpr std::size_t kMinCapacity = 1024;

  std::size_t home(const Key& key) const { return static_cast<std::size_t>(hashOf(key)) & mask_; }

  void rehash(std::size_t capacity) {  // a power of two
    std::vector<Slot> old(capacity);
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    for (const Slot& slot : old) {
      if (slot.empty()) continue;
      std::size_t s = home(slot.key);
      while (!slots_[s].empty()) s = (s + 1) & mask_;
      slots_[s] = slot;
    }
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
};

template <typename Key>
struct NumberedSlot {  // key and number side by side: one cache line per probe
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  Key key{};
  std::uint32_t number = kEmpty;
  bool empty() const { return number == kEmpty; }
};

struct PackedSlot {  // a packed key alone: 8 bytes, twice the keys per cache line
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::uint64_t key = kEmpty;
  bool empty() const { return key == kEmpty; }
};

}  // namespace detail

// Numbers the distinct keys 0, 1, 2 ... in the order they are first met.
template <typename Key>
class KeyNumbers : public detail::OpenTable<Key, detail::NumberedSlot<Key>> {
 public:
  // Room for `keys` keys before the first doubling.
  explicit KeyNumbers(std::size_t keys = 0) { this->reserve(keys); }

  // The number of `key`: its own, or size() before the call if it is new
  // (then `inserted` is set).
  std::uint32_t insert(const Key& key, bool& inserted) {
    auto& slot = this->slotFor(key);
    inserted = slot.empty();
    if (inserted) slot = {key, static_cast<std::uint32_t>(this->stored_++)};
    return slot.number;
  }

  std::size_t size() const { return this->stored_; }
};

// Voxel keys as they are (24 bytes): any coordinates.
using VoxelIndex = KeyNumbers<VoxelKey>;
// Keys packed into 64 bits by the caller (16-byte slots).
using PackedVoxelIndex = KeyNumbers<std::uint64_t>;

// Which packed keys were seen, in 8-byte slots: half a PackedVoxelIndex's
// memory, so twice as many keys stay in the caches (a picture's points
// need no numbers).
class PackedKeySet : public detail::OpenTable<std::uint64_t, detail::PackedSlot> {
 public:
  // Whether `key` is new (and now recorded).
  bool insert(std::uint64_t key) {
    if (key == detail::PackedSlot::kEmpty) {  // the empty slots' mark, kept aside
      const bool fresh = !has_empty_key_;
      has_empty_key_ = true;
      return fresh;
    }
    detail::PackedSlot& slot = slotFor(key);
    if (!slot.empty()) return false;
    slot.key = key;
    ++stored_;
    return true;
  }

  std::size_t size() const { return stored_ + (has_empty_key_ ? 1 : 0); }

  void clear() {
    OpenTable::clear();
    has_empty_key_ = false;
  }

 private:
  bool has_empty_key_ = false;
};

}  // namespace hba::voxel
