#include "page_points.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <mutex>
#include <string>

#include "hba/core/error.hpp"
#include "picture_points.hpp"
#include "scan_stream.hpp"

namespace hba::render {
namespace {

// The map is coarsened while it is read once it holds more than kSlack
// times the budget, and thinned to the budget at the end.
constexpr double kSlack = 1.25;
constexpr double kCoarsenWhileReading = 1.25;  // voxel growth each time
constexpr std::size_t kLookahead = 16;         // keys prefetched ahead of their insert

// Candidates of a chunk of scans, with their positions placed (relative to
// the map's origin) for the merge to key them at its voxel.
struct Chunk {
  std::vector<PagePoint> points;
  std::vector<Vec3f> world;
};

// Inserts `keys` into `seen` (prefetching the slots of keys a few ahead:
// the set's cache misses are most of the cost) and calls `keep(i)` for
// each one new. A key equal to the one before is not new (scans come ring
// by ring).
template <typename Keep>
void insertNew(voxel::PackedKeySet& seen, const std::vector<std::uint64_t>& keys, Keep&& keep) {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i + kLookahead < keys.size()) seen.prefetch(keys[i + kLookahead]);
    if (keys[i] == kOutsidePackedRange || (i > 0 && keys[i] == keys[i - 1]) || !seen.insert(keys[i]))
      continue;
    keep(i);
  }
}

// The packed keys of `world` at `voxel`, into `keys`.
const std::vector<std::uint64_t>& keysOf(const std::vector<Vec3f>& world, double voxel,
                                         std::vector<std::uint64_t>& keys) {
  keys.resize(world.size());
  const double inverse = 1.0 / voxel;
  // NaN falls outside the packed range.
  for (std::size_t i = 0; i < world.size(); ++i) keys[i] = packedVoxelKey(world[i].cast<double>(), inverse);
  return keys;
}

// Keeps the first point that falls into each world voxel; voxels more than
// 2^20 voxels from the origin are left out.
class FirstHits {
 public:
  FirstHits(double voxel, std::size_t room) : voxel_(voxel) { kept_.reserve(room); }
  double voxel() const { return voxel_; }
  std::size_t size() const { return kept_.size(); }
  // Room for `points` in the set at once: regrowing it touches fresh memory twice over.
  void reserve(std::size_t points) { index_.reserve(points); }
  void add(const Chunk& chunk) {
    insertNew(index_, keysOf(chunk.world, voxel_, keys_),
              [&](std::size_t i) { kept_.push_back(chunk.points[i]); });
  }
  // Thinned again at a coarser voxel, in place: the kept points stay in
  // scan order, so each coarse voxel keeps its first point again. The set's
  // table is refilled, not made anew: fresh memory costs page faults.
  void coarsen(double factor, const std::vector<Pose>& poses, const Vec3& origin) {
    voxel_ *= factor;
    index_.clear();
    std::vector<Vec3f> world(kept_.size());
    forEachPlaced(kept_, poses, origin, [&](std::size_t i, const Vec3& q) { world[i] = q.cast<float>(); });
    // Kept points move down over those dropped (insertNew goes in order).
    std::size_t kept = 0;
    std::vector<std::uint64_t> keys;
    insertNew(index_, keysOf(world, voxel_, keys), [&](std::size_t i) { kept_[kept++] = kept_[i]; });
    kept_.resize(kept);
  }
  // Exactly `budget` points kept (when there are more), an even share
  // everywhere: those whose index hashes lowest. In place and without a set,
  // where coarsening the voxel once more would cost as much as the merge.
  void thinTo(std::size_t budget) {
    if (kept_.size() <= budget) return;
    std::vector<std::uint64_t> ranks(kept_.size());
    for (std::size_t i = 0; i < ranks.size(); ++i) ranks[i] = voxel::mixBits(i);
    std::vector<std::uint64_t> sorted = ranks;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(budget - 1), sorted.end());
    const std::uint64_t highest = sorted[budget - 1];
    std::size_t kept = 0;
    for (std::size_t i = 0; i < kept_.size() && kept < budget; ++i)
      if (ranks[i] <= highest) kept_[kept++] = kept_[i];
    kept_.resize(kept);
  }
  std::vector<PagePoint>& kept() { return kept_; }

 private:
  double voxel_;
  voxel::PackedKeySet index_;
  std::vector<PagePoint> kept_;
  std::vector<std::uint64_t> keys_;  // a chunk's, reused
};

// Chunks' buffers handed back after their merge and filled again by a later
// chunk: fresh memory costs a page fault every 4 KiB, dear on virtual machines.
class ChunkPool {
 public:
  Chunk take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) return {};
    Chunk chunk = std::move(free_.back());
    free_.pop_back();
    chunk.points.clear();
    chunk.world.clear();
    return chunk;
  }
  void give(Chunk&& chunk) {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(chunk));
  }

 private:
  std::mutex mutex_;
  std::vector<Chunk> free_;
};

// A reading thread's working memory, kept from chunk to chunk (its table
// is emptied, not faulted in again) and freed with the call.
struct Scratch {
  voxel::PackedKeySet seen;
  std::vector<std::uint64_t> keys;
  std::vector<Vec3f> world;
};

// One chunk's scans thinned on their own at the start voxel, into `out`:
// the same candidates whatever the timing of the threads.
void readChunk(const io::ScanSource& scans, const std::vector<Pose>& poses, std::size_t chunk, double voxel,
               double scans_voxel, const Vec3& origin, Scratch& scratch, Chunk& out) {
  const std::size_t first = chunk * kChunk;
  const std::size_t end = std::min(scans.size(), first + kChunk);
  voxel::PackedKeySet& seen = scratch.seen;
  std::vector<Vec3f>& world = scratch.world;
  seen.clear();
  for (std::size_t i = first; i < end; ++i) {
    const PointCloud scan = loadAt(scans, i, voxel, scans_voxel);
    const Mat3 R = poses[i].R();
    const Vec3 t = poses[i].t - origin;
    world.resize(scan.size());
    for (std::size_t k = 0; k < scan.size(); ++k)
      world[k] = (R * (scan.origin + scan.points[k].cast<double>()) + t).cast<float>();
    insertNew(seen, keysOf(world, voxel, scratch.keys), [&](std::size_t k) {
      out.points.push_back({static_cast<std::uint32_t>(i), scan.hasIntensity() ? scan.intensity[k] : 0.0f,
                            (scan.origin + scan.points[k].cast<double>()).cast<float>()});
      out.world.push_back(world[k]);
    });
  }
}

}  // namespace

PagePoints samplePagePoints(const io::ScanSource& scans, const std::vector<Pose>& poses, std::size_t budget,
                            double start_voxel, double scans_voxel, const MemoryBudget& memory) {
  if (poses.size() != scans.size()) {
    throw Error("there are " + std::to_string(scans.size()) + " scans but " + std::to_string(poses.size()) +
                " poses were given");
  }
  if (budget == 0 || !(start_voxel > 0.0)) throw Error("the page's point budget and voxel must be positive");
  const Vec3 origin = poses.empty() ? Vec3::Zero() : poses.front().t;
  // Room for the most the map holds: pages never touched are not memory.
  const auto most = static_cast<std::size_t>(kSlack * static_cast<double>(budget)) + 1;
  FirstHits map(start_voxel, most);
  bool intensity = false;
  const std::size_t chunks = (scans.size() + kChunk - 1) / kChunk;
  ChunkPool pool;
  tbb::enumerable_thread_specific<Scratch> scratch;
  const std::function<Chunk(std::size_t)> read = [&](std::size_t chunk) {
    Chunk part = pool.take();
    readChunk(scans, poses, chunk, start_voxel, scans_voxel, origin, scratch.local(), part);
    return part;
  };
  const std::function<void(std::size_t, Chunk&)> merge = [&](std::size_t chunk, Chunk& part) {
    for (const PagePoint& p : part.points) intensity = intensity || p.intensity != 0.0f;
    // As many points as the first chunk's in each chunk would be the most the map can hold.
    if (chunk == 0) map.reserve(std::min(most, part.points.size() * chunks));
    map.add(part);
    pool.give(std::move(part));
    while (static_cast<double>(map.size()) > kSlack * static_cast<double>(budget))
      map.coarsen(kCoarsenWhileReading, poses, origin);
    if (memory.exceeded()) {
      throw memory.exceededBy("the page's map (" + std::to_string(map.size()) + " points after " +
                              std::to_string(std::min(scans.size(), (chunk + 1) * kChunk)) + " of " +
                              std::to_string(scans.size()) + " scans)");
    }
  };
  Progress progress("reading the scans for the report page", chunks, "chunks of " + std::to_string(kChunk));
  streamScans(upTo(chunks), read, merge, progress);
  const std::size_t thinned_from = map.size();
  map.thinTo(budget);

  PagePoints out;
  out.voxel = map.voxel();
  out.has_intensity = intensity;
  out.kept_share =
      static_cast<double>(map.size()) / static_cast<double>(std::max<std::size_t>(1, thinned_from));
  out.points = std::move(map.kept());
  return out;
}

}  // namespace hba::render
