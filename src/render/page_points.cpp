#include "page_points.hpp"

#include <atomic>
#include <cmath>
#include <functional>
#include <string>

#include "hba/core/error.hpp"
#include "picture_points.hpp"
#include "scan_stream.hpp"

namespace hba::render {
namespace {

// The map is thinned while it is read once it holds more than kSlack times
// the budget, and to the budget at the end.
constexpr double kSlack = 1.25;
constexpr double kCoarsenWhileReading = 1.25;  // voxel growth each time
constexpr double kCoarsenToFit = 1.1;
constexpr std::size_t kLookahead = 16;  // keys prefetched ahead of their insert
constexpr std::size_t kPageChunk = 100;

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
void insertNew(voxel::PackedVoxelSet& seen, const std::vector<std::uint64_t>& keys, Keep&& keep) {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i + kLookahead < keys.size()) seen.prefetch(keys[i + kLookahead]);
    if (keys[i] == kOutsidePackedRange || (i > 0 && keys[i] == keys[i - 1]) || !seen.insert(keys[i]))
      continue;
    keep(i);
  }
}

std::vector<std::uint64_t>& keysOf(const std::vector<Vec3f>& world, double voxel) {
  thread_local std::vector<std::uint64_t> keys;
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
  void add(const Chunk& chunk) {
    insertNew(index_, keysOf(chunk.world, voxel_), [&](std::size_t i) { kept_.push_back(chunk.points[i]); });
  }
  // Thinned again at a coarser voxel, in place: the kept points stay in
  // scan order, so each coarse voxel keeps its first point again. The set's
  // table is refilled, not made anew: fresh memory costs page faults.
  void coarsen(double factor, const std::vector<Pose>& poses, const Vec3& origin) {
    voxel_ *= factor;
    index_.clear();
    const double inverse = 1.0 / voxel_;
    std::uint32_t scan = ~0u;  // the points come scan by scan: one rotation matrix a scan
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
    std::size_t kept = 0;
    for (const PagePoint& p : kept_) {
      if (p.scan != scan) {
        scan = p.scan;
        R = poses[scan].R();
        t = poses[scan].t - origin;
      }
      const Vec3f world = (R * p.local.cast<double>() + t).cast<float>();
      const std::uint64_t key = packedVoxelKey(world.cast<double>(), inverse);
      if (key != kOutsidePackedRange && index_.insert(key)) kept_[kept++] = p;
    }
    kept_.resize(kept);
  }
  std::vector<PagePoint>& kept() { return kept_; }

 private:
  double voxel_;
  voxel::PackedVoxelSet index_;
  std::vector<PagePoint> kept_;
};

// One chunk's scans thinned on their own at the start voxel: the same
// candidates whatever the timing of the threads. `expected`: room to make
// at once (the last chunk's count; a guess).
Chunk readChunk(const io::ScanSource& scans, const std::vector<Pose>& poses, std::size_t chunk, double voxel,
                double scans_voxel, const Vec3& origin, std::size_t expected) {
  const std::size_t first = chunk * kPageChunk;
  const std::size_t end = std::min(scans.size(), first + kPageChunk);
  // One set a thread, emptied for each chunk: its table is not faulted in again.
  thread_local voxel::PackedVoxelSet seen;
  seen.clear();
  Chunk out;
  out.points.reserve(expected);
  out.world.reserve(expected);
  std::vector<Vec3f> world;
  for (std::size_t i = first; i < end; ++i) {
    const PointCloud scan = loadAt(scans, i, voxel, scans_voxel);
    const Mat3 R = poses[i].R();
    const Vec3 t = poses[i].t - origin;
    world.resize(scan.size());
    for (std::size_t k = 0; k < scan.size(); ++k)
      world[k] = (R * (scan.origin + scan.points[k].cast<double>()) + t).cast<float>();
    insertNew(seen, keysOf(world, voxel), [&](std::size_t k) {
      out.points.push_back({static_cast<std::uint32_t>(i), scan.hasIntensity() ? scan.intensity[k] : 0.0f,
                            (scan.origin + scan.points[k].cast<double>()).cast<float>()});
      out.world.push_back(world[k]);
    });
  }
  return out;
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
  FirstHits map(start_voxel, static_cast<std::size_t>(kSlack * static_cast<double>(budget)) + 1);
  bool intensity = false;
  const std::size_t chunks = (scans.size() + kPageChunk - 1) / kPageChunk;
  std::atomic<std::size_t> chunk_points{0};
  const std::function<Chunk(std::size_t)> read = [&](std::size_t chunk) {
    Chunk part = readChunk(scans, poses, chunk, start_voxel, scans_voxel, origin,
                           chunk_points.load(std::memory_order_relaxed) * 5 / 4);
    chunk_points.store(part.points.size(), std::memory_order_relaxed);
    return part;
  };
  const std::function<void(std::size_t, Chunk&)> merge = [&](std::size_t chunk, Chunk& part) {
    for (const PagePoint& p : part.points) intensity = intensity || p.intensity != 0.0f;
    map.add(part);
    while (static_cast<double>(map.size()) > kSlack * static_cast<double>(budget))
      map.coarsen(kCoarsenWhileReading, poses, origin);
    if (memory.exceeded()) {
      throw memory.exceededBy("the page's map (" + std::to_string(map.size()) + " points after " +
                              std::to_string(std::min(scans.size(), (chunk + 1) * kPageChunk)) + " of " +
                              std::to_string(scans.size()) + " scans)");
    }
  };
  Progress progress("reading the scans for the report page", chunks,
                    "chunks of " + std::to_string(kPageChunk));
  streamScans(upTo(chunks), read, merge, progress);
  while (map.size() > budget) map.coarsen(kCoarsenToFit, poses, origin);

  PagePoints out;
  out.voxel = map.voxel();
  out.has_intensity = intensity;
  out.points = std::move(map.kept());
  return out;
}

}  // namespace hba::render
