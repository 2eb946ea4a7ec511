// The one key table (key_table.hpp): the same answers as the standard
// containers, through growth, collisions, clearing and the key that marks
// a set's empty slots.
#include <gtest/gtest.h>

#include <random>
#include <unordered_map>
#include <unordered_set>

#include "hba/voxel/key_table.hpp"

namespace hba::voxel {
namespace {

TEST(PackedKeySet, AgreesWithAStandardSetThroughGrowth) {
  PackedKeySet set;
  std::unordered_set<std::uint64_t> reference;
  std::mt19937_64 random(5);
  for (int i = 0; i < 200000; ++i) {
    // Few distinct keys in the low bits: repeats, and keys that share homes.
    const std::uint64_t key = i % 3 == 0 ? random() : (random() % 5000) << 42 | (random() % 7);
    if (i % 5 == 0) set.prefetch(key);
    ASSERT_EQ(set.insert(key), reference.insert(key).second) << i;
  }
  EXPECT_EQ(set.size(), reference.size());
}

TEST(PackedKeySet, TheEmptyMarkIsAKeyLikeAnother) {
  PackedKeySet set;
  const std::uint64_t mark = ~std::uint64_t{0};
  EXPECT_TRUE(set.insert(mark));
  EXPECT_FALSE(set.insert(mark));
  EXPECT_TRUE(set.insert(0));
  EXPECT_FALSE(set.insert(0));
  EXPECT_EQ(set.size(), 2u);
  set.reserve(5000);  // regrowing keeps what is there
  EXPECT_FALSE(set.insert(mark));
  EXPECT_FALSE(set.insert(0));
  EXPECT_TRUE(set.insert(mark - 1));
  EXPECT_EQ(set.size(), 3u);
}

TEST(PackedKeySet, ClearedItForgetsEveryKeyAndServesAgain) {
  PackedKeySet set;
  const std::uint64_t mark = ~std::uint64_t{0};
  for (std::uint64_t k = 0; k < 3000; ++k) set.insert(k * 977);
  set.insert(mark);
  set.clear();
  EXPECT_EQ(set.size(), 0u);
  EXPECT_TRUE(set.insert(mark));
  for (std::uint64_t k = 0; k < 3000; ++k) ASSERT_TRUE(set.insert(k * 977)) << k;
  EXPECT_FALSE(set.insert(977));
  EXPECT_EQ(set.size(), 3001u);
}

TEST(PackedVoxelIndex, NumbersKeysInFirstSeenOrder) {
  PackedVoxelIndex index;
  std::unordered_map<std::uint64_t, std::uint32_t> reference;
  std::mt19937_64 random(9);
  for (int i = 0; i < 100000; ++i) {
    const std::uint64_t key = random() % 30000;
    bool inserted = false;
    const std::uint32_t number = index.insert(key, inserted);
    const auto [it, fresh] = reference.emplace(key, static_cast<std::uint32_t>(reference.size()));
    ASSERT_EQ(inserted, fresh);
    ASSERT_EQ(number, it->second);
  }
  EXPECT_EQ(index.size(), reference.size());
}

TEST(VoxelIndex, NumbersVoxelKeysInFirstSeenOrderAndServesAgainWhenCleared) {
  VoxelIndex index(10);  // far too small: grows many times
  std::mt19937 random(3);
  std::uniform_int_distribution<long> coordinate(-40, 40);  // keys either side of 0
  for (int round = 0; round < 2; ++round) {
    std::unordered_map<VoxelKey, std::uint32_t, VoxelKeyHash> reference;
    for (int i = 0; i < 50000; ++i) {
      const VoxelKey key{coordinate(random), coordinate(random), coordinate(random) / 8};
      if (i % 3 == 0) index.prefetch(key);
      bool inserted = false;
      const std::uint32_t number = index.insert(key, inserted);
      const auto [it, fresh] = reference.emplace(key, static_cast<std::uint32_t>(reference.size()));
      ASSERT_EQ(inserted, fresh) << round << " " << i;
      ASSERT_EQ(number, it->second) << round << " " << i;
    }
    EXPECT_EQ(index.size(), reference.size());
    index.clear();
    EXPECT_EQ(index.size(), 0u);
  }
}

}  // namespace
}  // namespace hba::voxel
