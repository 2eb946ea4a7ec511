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

struct Candidate {
  std::uint32_t scan = 0;
  float intensity = 0.0f;
  Vec3f local = Vec3f::Zero();
  Vec3f world = Vec3f::Zero();  // placed, relative to the map's origin
};

// Keeps the first candidate that falls into each world voxel; voxels more
// than 2^20 voxels from the origin are left out.
class FirstHits {
 public:
  explicit FirstHits(double voxel) : voxel_(voxel) {}
  double voxel() const { return voxel_; }
  std::size_t size() const { return kept_.size(); }
  // Keys first, then the inserts, each prefetching the slot of a key a few
  // candidates ahead: the set's cache misses are most of the cost.
  void add(const std::vector<Candidate>& candidates) {
    thread_local std::vector<std::uint64_t> keys;
    keys.resize(candidates.size());
    const double inverse = 1.0 / voxel_;
    for (std::size_t i = 0; i < candidates.size(); ++i)
      keys[i] = packedVoxelKey(candidates[i].world.cast<double>(), inverse);
    constexpr std::size_t kLookahead = 16;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (i + kLookahead < keys.size()) index_.prefetch(keys[i + kLookahead]);
      if (keys[i] != kOutsidePackedRange && index_.insert(keys[i])) kept_.push_back(candidates[i]);
    }
  }
  // Thinned again at a coarser voxel; the kept points stay in scan order,
  // so each coarse voxel keeps its first point again.
  void coarsen(double factor) {
    std::vector<Candidate> old = std::move(kept_);
    kept_ = {};
    index_ = {};
    voxel_ *= factor;
    add(old);
  }
  std::vector<Candidate>& kept() { return kept_; }

 private:
  double voxel_;
  voxel::PackedVoxelSet index_;
  std::vector<Candidate> kept_;
};

// One chunk's scans thinned on their own at the start voxel: the same
// candidates whatever the timing of the threads. `expected`: room to make
// at once (the last chunk's count; a guess).
std::vector<Candidate> readChunk(const io::ScanSource& scans, const std::vector<Pose>& poses,
                                 std::size_t chunk, double voxel, double scans_voxel, const Vec3& origin,
                                 std::size_t expected) {
  const std::size_t first = chunk * kChunk;
  const std::size_t end = std::min(scans.size(), first + kChunk);
  voxel::PackedVoxelSet seen;
  seen.reserve(expected);
  std::vector<Candidate> kept;
  kept.reserve(expected);
  const double inverse = 1.0 / voxel;
  std::vector<std::uint64_t> keys;
  std::vector<Vec3f> world;
  for (std::size_t i = first; i < end; ++i) {
    const PointCloud scan = loadAt(scans, i, voxel, scans_voxel);
    const Mat3 R = poses[i].R();
    const Vec3 t = poses[i].t - origin;
    keys.resize(scan.size());
    world.resize(scan.size());
    for (std::size_t k = 0; k < scan.size(); ++k) {
      world[k] = (R * (scan.origin + scan.points[k].cast<double>()) + t).cast<float>();
      // As the merge computes it: from the float position (NaN falls outside).
      keys[k] = packedVoxelKey(world[k].cast<double>(), inverse);
    }
    // Then the inserts, each prefetching the slot of a key a few points ahead.
    constexpr std::size_t kLookahead = 16;
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (k + kLookahead < keys.size()) seen.prefetch(keys[k + kLookahead]);
      // Scans come ring by ring: a point in the voxel of the one before is not new.
      if (keys[k] == kOutsidePackedRange || (k > 0 && keys[k] == keys[k - 1]) || !seen.insert(keys[k]))
        continue;
      kept.push_back({static_cast<std::uint32_t>(i), scan.hasIntensity() ? scan.intensity[k] : 0.0f,
                      (scan.origin + scan.points[k].cast<double>()).cast<float>(), world[k]});
    }
  }
  return kept;
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
  FirstHits map(start_voxel);
  bool intensity = false;
  const std::size_t chunks = (scans.size() + kChunk - 1) / kChunk;
  std::atomic<std::size_t> chunk_points{0};
  const std::function<std::vector<Candidate>(std::size_t)> read = [&](std::size_t chunk) {
    std::vector<Candidate> part = readChunk(scans, poses, chunk, start_voxel, scans_voxel, origin,
                                            chunk_points.load(std::memory_order_relaxed) * 5 / 4);
    chunk_points.store(part.size(), std::memory_order_relaxed);
    return part;
  };
  const std::function<void(std::size_t, std::vector<Candidate>&)> merge = [&](std::size_t chunk,
                                                                              std::vector<Candidate>& part) {
    for (const Candidate& c : part) intensity = intensity || c.intensity != 0.0f;
    map.add(part);
    while (static_cast<double>(map.size()) > kSlack * static_cast<double>(budget))
      map.coarsen(kCoarsenWhileReading);
    if (memory.exceeded()) {
      throw memory.exceededBy("the page's map (" + std::to_string(map.size()) + " points after " +
                              std::to_string(std::min(scans.size(), (chunk + 1) * kChunk)) + " of " +
                              std::to_string(scans.size()) + " scans)");
    }
  };
  Progress progress("reading the scans for the report page", chunks, "chunks of " + std::to_string(kChunk));
  streamScans(upTo(chunks), read, merge, progress);
  while (map.size() > budget) map.coarsen(kCoarsenToFit);

  PagePoints out;
  out.voxel = map.voxel();
  out.scan.reserve(map.size());
  out.local.reserve(map.size());
  if (intensity) out.intensity.reserve(map.size());
  for (const Candidate& c : map.kept()) {
    out.scan.push_back(c.scan);
    out.local.push_back(c.local);
    if (intensity) out.intensity.push_back(c.intensity);
  }
  return out;
}

}  // namespace hba::render
