#include "hba/voxel/downsample.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

// Running sums of one occupied voxel, in double so that thousands of float
// points average without loss.
struct CellSum {
  Vec3 position = Vec3::Zero();
  double intensity = 0.0;
  std::uint32_t count = 0;
};

// Cell keys packed into one 64-bit word when the cloud spans fewer than 2^21
// cells per axis (200 km at 0.1 m), relative to its lowest cell so that
// far-from-origin (UTM) coordinates pack too. Anything else uses full keys.
constexpr int kPackedBits = 21;
constexpr std::int64_t kPackedSpan = std::int64_t{1} << kPackedBits;

std::uint64_t mix(std::uint64_t h) {
  // Finalizer of MurmurHash3: spreads every input bit over the low bits the
  // power-of-two table uses.
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  return h ^ (h >> 33);
}

std::uint64_t hashOf(std::uint64_t packed) { return mix(packed); }
std::uint64_t hashOf(const VoxelKey& key) {
  return mix(static_cast<std::uint64_t>(key.x) ^ mix(static_cast<std::uint64_t>(key.y) ^
                                                     mix(static_cast<std::uint64_t>(key.z))));
}

// Open-addressing table from cell key to cell number; numbers are handed out
// in the order cells are first hit, which fixes the output order.
template <typename Key>
class CellTable {
 public:
  explicit CellTable(std::size_t points) {
    std::size_t capacity = 16;
    while (capacity < 2 * points) capacity *= 2;  // load factor <= 0.5
    slots_.resize(capacity);
    mask_ = capacity - 1;
  }

  // Starts loading the slot of a key needed soon: the table is larger than the
  // caches, and hiding that miss is most of the speed.
  void prefetch(const Key& key) const { __builtin_prefetch(&slots_[hashOf(key) & mask_]); }

  // The cell number of `key`, or `next` (recorded) if the key is new.
  std::uint32_t find(const Key& key, std::uint32_t next) {
    for (std::size_t i = hashOf(key) & mask_;; i = (i + 1) & mask_) {
      Slot& slot = slots_[i];
      if (slot.cell == kEmpty) {
        slot = {key, next};
        return next;
      }
      if (slot.key == key) return slot.cell;
    }
  }

 private:
  static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  struct Slot {  // key and cell side by side: one cache line per probe
    Key key{};
    std::uint32_t cell = kEmpty;
  };
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
};

// Sums every point into its cell; `key_of(i)` gives point i's key.
template <typename Key, typename KeyOf>
std::vector<CellSum> sumByCell(const PointCloud& cloud, KeyOf key_of) {
  constexpr std::size_t kLookahead = 16;  // points between a prefetch and its use
  const std::size_t n = cloud.size();
  std::vector<Key> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = key_of(i);

  const bool with_intensity = cloud.hasIntensity();
  CellTable<Key> table(n);
  std::vector<CellSum> sums;
  sums.reserve(n / 4);  // scans keep roughly this share at usual voxel sizes
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kLookahead < n) table.prefetch(keys[i + kLookahead]);
    const auto cell = table.find(keys[i], static_cast<std::uint32_t>(sums.size()));
    if (cell == sums.size()) sums.emplace_back();
    CellSum& sum = sums[cell];
    sum.position += cloud.points[i].cast<double>();
    if (with_intensity) sum.intensity += cloud.intensity[i];
    ++sum.count;
  }
  return sums;
}

// The lowest cell of a cloud and whether all its cells pack into 64 bits.
struct CellBounds {
  VoxelKey low;
  bool packable = false;
};

CellBounds boundsOf(const PointCloud& cloud, double size) {
  Vec3f low = Vec3f::Constant(std::numeric_limits<float>::max());
  Vec3f high = Vec3f::Constant(std::numeric_limits<float>::lowest());
  bool finite = true;
  for (const Vec3f& p : cloud.points) {
    finite = finite && p.allFinite();
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  CellBounds bounds;
  if (!finite || cloud.empty()) return bounds;
  bounds.low = VoxelKey::of(low.cast<double>(), size);
  const VoxelKey top = VoxelKey::of(high.cast<double>(), size);
  bounds.packable = top.x - bounds.low.x < kPackedSpan && top.y - bounds.low.y < kPackedSpan &&
                    top.z - bounds.low.z < kPackedSpan;
  return bounds;
}

}  // namespace

// Rule: each occupied voxel becomes the centroid of its points (and the mean
// intensity). The centroid averages range noise instead of keeping one noisy
// sample, which matters for plane residuals. Output order is the order in
// which voxels are first hit while scanning the input, and each centroid sums
// its points in input order, so the result depends on neither hashing nor
// the key representation.
//
// One pass through a flat hash table: no sorting and no allocation per cell,
// which matters because every scan and every keyframe goes through here.
PointCloud downsample(const PointCloud& cloud, double voxel_size) {
  if (!(voxel_size > 0.0)) return cloud;
  const auto keyOf = [&](std::size_t i) { return VoxelKey::of(cloud.points[i].cast<double>(), voxel_size); };
  const CellBounds bounds = boundsOf(cloud, voxel_size);
  std::vector<CellSum> sums;
  if (bounds.packable) {
    sums = sumByCell<std::uint64_t>(cloud, [&](std::size_t i) {
      const VoxelKey key = keyOf(i);
      return static_cast<std::uint64_t>(key.x - bounds.low.x) << (2 * kPackedBits) |
             static_cast<std::uint64_t>(key.y - bounds.low.y) << kPackedBits |
             static_cast<std::uint64_t>(key.z - bounds.low.z);
    });
  } else {
    sums = sumByCell<VoxelKey>(cloud, keyOf);
  }

  const bool with_intensity = cloud.hasIntensity();
  PointCloud out;
  out.reserve(sums.size(), with_intensity);
  for (const CellSum& sum : sums) {
    const double inv = 1.0 / static_cast<double>(sum.count);
    const Vec3f centroid = (sum.position * inv).cast<float>();
    if (with_intensity) {
      out.add(centroid, static_cast<float>(sum.intensity * inv));
    } else {
      out.add(centroid);
    }
  }
  return out;
}

}  // namespace hba::voxel
