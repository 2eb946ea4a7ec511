#include "cell_assignment.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "hba/voxel/key_table.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

// Cell keys packed into one 64-bit word when the cloud spans fewer than 2^21
// cells per axis (200 km at 0.1 m), relative to its lowest cell so that
// far-from-origin (UTM) coordinates pack too. Anything else uses full keys.
constexpr int kPackedBits = 21;
constexpr std::int64_t kPackedSpan = std::int64_t{1} << kPackedBits;

// The lowest cell of a cloud and whether all its cells pack into 64 bits.
struct CellBounds {
  VoxelKey low;
  VoxelKey span;  // cells along each axis
  bool packable = false;
  // Cells of the box the cloud spans (saturating: huge boxes just count as huge).
  std::uint64_t boxCells() const {
    if (!packable) return ~std::uint64_t{0};
    return static_cast<std::uint64_t>(span.x) * static_cast<std::uint64_t>(span.y) *
           static_cast<std::uint64_t>(span.z);
  }
};

CellBounds boundsOf(const std::vector<Vec3f>& points, double size) {
  Vec3f low = Vec3f::Constant(std::numeric_limits<float>::max());
  Vec3f high = Vec3f::Constant(std::numeric_limits<float>::lowest());
  bool finite = true;
  for (const Vec3f& p : points) {
    finite = finite && p.allFinite();
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  CellBounds bounds;
  if (!finite || points.empty()) return bounds;
  bounds.low = VoxelKey::of(low.cast<double>(), size);
  const VoxelKey top = VoxelKey::of(high.cast<double>(), size);
  bounds.packable = top.x - bounds.low.x < kPackedSpan && top.y - bounds.low.y < kPackedSpan &&
                    top.z - bounds.low.z < kPackedSpan;
  bounds.span = {top.x - bounds.low.x + 1, top.y - bounds.low.y + 1, top.z - bounds.low.z + 1};
  return bounds;
}

// Clouds of this many points or more (refinement blocks of millions) take
// their keys in parallel, as each point's key is independent of the others.
constexpr std::size_t kParallelFrom = std::size_t{1} << 20;

// Runs body(i) for i in [begin, end), in parallel when `parallel`.
template <typename Body>
void forEachPoint(std::size_t begin, std::size_t end, bool parallel, const Body& body) {
  if (!parallel) {
    for (std::size_t i = begin; i < end; ++i) body(i);
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 1 << 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) body(i);
                      });
  }
}

template <typename Body>
void forEachPoint(std::size_t points, const Body& body) {
  forEachPoint(0, points, points >= kParallelFrom, body);
}

// Cell numbers in a grid over the whole box a small cloud spans, indexed by
// the cell itself: what KeyNumbers gives for the same keys in the same
// order, without a hash or a probe (a window's points at 1 m fill a box of
// a few hundred thousand cells).
class GridNumbers {
 public:
  explicit GridNumbers(std::uint64_t cells) : slots_(cells, 0) {}
  void prefetch(std::uint64_t cell) const { __builtin_prefetch(&slots_[cell]); }
  std::uint32_t insert(std::uint64_t cell, bool& inserted) {
    std::uint32_t& slot = slots_[cell];
    inserted = slot == 0;
    if (inserted) slot = ++numbered_;  // stored one up: 0 is "not met"
    return slot - 1;
  }

 private:
  std::vector<std::uint32_t> slots_;
  std::uint32_t numbered_ = 0;
};

// Numbers the cells of points [begin, end) in their first-hit order with
// `table`, from 0: each point's number into cell_of_point, each new cell's
// first point into `first`. Keys are taken a chunk at a time, just before
// they are numbered, so that they stay in the cache.
template <typename Key, typename KeyOfPoint, typename Table>
void numberRange(std::size_t begin, std::size_t end, const KeyOfPoint& keyOf, Table& table,
                 std::vector<std::uint32_t>& cell_of_point, std::vector<std::uint32_t>& first) {
  constexpr std::size_t kLookahead = 16;                // points between a prefetch and its use
  constexpr std::size_t kChunk = std::size_t{1} << 16;  // keys held at once
  // A chunk's keys and the lookahead's beyond it (taken again with the next
  // chunk: a few keys a chunk).
  std::vector<Key> keys(std::min(end - begin, kChunk + kLookahead));
  Key previous{};
  for (std::size_t from = begin; from < end; from += kChunk) {
    const std::size_t to = std::min(end, from + kChunk);
    const std::size_t known = std::min(end, to + kLookahead);
    for (std::size_t i = from; i < known; ++i) keys[i - from] = keyOf(i);
    for (std::size_t i = from; i < to; ++i) {
      const Key& key = keys[i - from];
      // Scans come ring by ring: a point mostly shares the cell of the one
      // before it, which then needs no lookup.
      if (i > begin && key == previous) {
        cell_of_point[i] = cell_of_point[i - 1];
        continue;
      }
      if (i + kLookahead < end) table.prefetch(keys[i + kLookahead - from]);
      bool inserted = false;
      const std::uint32_t cell = table.insert(key, inserted);
      if (inserted) first.push_back(static_cast<std::uint32_t>(i));
      cell_of_point[i] = cell;
      previous = key;
    }
  }
}

// How many ranges of a cloud of `n` points are numbered side by side.
std::size_t rangesFor(std::size_t n) {
  if (n < kParallelFrom) return 1;
  const auto threads = static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
  return std::min<std::size_t>(threads, 64);
}

// The first point of each of `ranges` equal ranges of `n` points, and n.
std::vector<std::size_t> rangeStarts(std::size_t n, std::size_t ranges) {
  std::vector<std::size_t> start(ranges + 1);
  for (std::size_t k = 0; k <= ranges; ++k) start[k] = n * k / ranges;
  return start;
}

// Numbers the cells of points 0 .. n-1 (their keys from keyOf(i)) in
// first-hit order. A large cloud (a refinement block of millions) is cut
// into ranges numbered side by side, each from 0 in a table of its own;
// then each later range's cells, in their first-hit order, take the
// numbers of the same keys before them or the next free ones: the very
// numbering of one pass in point order, for any number of ranges.
template <typename Key, typename KeyOfPoint>
CellAssignment numberCells(std::size_t n, const KeyOfPoint& keyOf, std::size_t points_per_cell) {
  const std::size_t per_cell = std::max<std::size_t>(points_per_cell, 1);
  CellAssignment out;
  out.cell_of_point.resize(n);
  const std::size_t ranges = rangesFor(n);
  if (ranges == 1) {  // scans and windows: thousands of calls, no task to start
    KeyNumbers<Key> table(n / per_cell);
    numberRange<Key>(0, n, keyOf, table, out.cell_of_point, out.first_point_of_cell);
    return out;
  }
  const std::vector<std::size_t> start = rangeStarts(n, ranges);
  std::vector<std::optional<KeyNumbers<Key>>> tables(ranges);
  std::vector<std::vector<std::uint32_t>> first(ranges);
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t k) {
    tables[k].emplace((start[k + 1] - start[k]) / per_cell);
    numberRange<Key>(start[k], start[k + 1], keyOf, *tables[k], out.cell_of_point, first[k]);
  });
  out.first_point_of_cell = std::move(first[0]);
  KeyNumbers<Key>& numbered = *tables[0];
  std::vector<std::vector<std::uint32_t>> renumber(ranges);
  for (std::size_t k = 1; k < ranges; ++k) {
    tables[k].reset();
    renumber[k].resize(first[k].size());
    for (std::size_t c = 0; c < first[k].size(); ++c) {
      bool inserted = false;
      renumber[k][c] = numbered.insert(keyOf(first[k][c]), inserted);
      if (inserted) out.first_point_of_cell.push_back(first[k][c]);
    }
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(start[1], n, 1 << 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::size_t k = static_cast<std::size_t>(
                          std::upper_bound(start.begin(), start.end(), range.begin()) - start.begin() - 1);
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        while (i >= start[k + 1]) ++k;
                        out.cell_of_point[i] = renumber[k][out.cell_of_point[i]];
                      }
                    });
  return out;
}

}  // namespace

// A cloud whose box holds at most this many cells a point is numbered in a
// grid over the box: clearing the grid costs less than hashing the points.
constexpr std::uint64_t kGridCellsPerPoint = 4;

CellAssignment assignCells(const std::vector<Vec3f>& points, double size, std::size_t points_per_cell) {
  const KeyOf keyOf(size);
  // Large clouds are numbered in ranges side by side (numberCells).
  const CellBounds bounds = boundsOf(points, size);
  const std::size_t n = points.size();
  if (n < kParallelFrom && bounds.boxCells() <= kGridCellsPerPoint * n) {
    const auto span_y = static_cast<std::uint64_t>(bounds.span.y);
    const auto span_z = static_cast<std::uint64_t>(bounds.span.z);
    auto cellOf = [&](std::size_t i) {
      const VoxelKey key = keyOf(points[i]);
      return (static_cast<std::uint64_t>(key.x - bounds.low.x) * span_y +
              static_cast<std::uint64_t>(key.y - bounds.low.y)) *
                 span_z +
             static_cast<std::uint64_t>(key.z - bounds.low.z);
    };
    CellAssignment out;
    out.cell_of_point.resize(n);
    GridNumbers grid(bounds.boxCells());
    numberRange<std::uint64_t>(0, n, cellOf, grid, out.cell_of_point, out.first_point_of_cell);
    return out;
  }
  if (!bounds.packable) {
    return numberCells<VoxelKey>(
        points.size(), [&](std::size_t i) { return keyOf(points[i]); }, points_per_cell);
  }
  return numberCells<std::uint64_t>(
      points.size(),
      [&](std::size_t i) {
        const VoxelKey key = keyOf(points[i]);
        return static_cast<std::uint64_t>(key.x - bounds.low.x) << (2 * kPackedBits) |
               static_cast<std::uint64_t>(key.y - bounds.low.y) << kPackedBits |
               static_cast<std::uint64_t>(key.z - bounds.low.z);
      },
      points_per_cell);
}

std::optional<CellAssignment> coarsenCells(const CellAssignment& fine, const std::vector<Vec3f>& points,
                                           double coarse_size) {
  const KeyOf keyOf(coarse_size);
  std::vector<VoxelKey> coarse_key(fine.cells());
  for (std::size_t c = 0; c < fine.cells(); ++c) coarse_key[c] = keyOf(points[fine.first_point_of_cell[c]]);
  // Each point must share its fine cell's coarse cell (always so for
  // power-of-two ratios; rounding at other edges could split a fine cell).
  std::atomic<bool> nested{true};
  forEachPoint(points.size(), [&](std::size_t i) {
    if (!(keyOf(points[i]) == coarse_key[fine.cell_of_point[i]]))
      nested.store(false, std::memory_order_relaxed);
  });
  if (!nested.load()) return std::nullopt;
  // Fine cells come in first-hit order, so numbering their coarse cells as
  // they come numbers those in first-hit order too, as assignCells would.
  KeyNumbers<VoxelKey> table(fine.cells());
  std::vector<std::uint32_t> coarse_of_fine(fine.cells());
  CellAssignment out;
  for (std::size_t c = 0; c < fine.cells(); ++c) {
    bool inserted = false;
    coarse_of_fine[c] = table.insert(coarse_key[c], inserted);
    if (inserted) out.first_point_of_cell.push_back(fine.first_point_of_cell[c]);
  }
  out.cell_of_point.resize(fine.cell_of_point.size());
  for (std::size_t i = 0; i < out.cell_of_point.size(); ++i) {
    out.cell_of_point[i] = coarse_of_fine[fine.cell_of_point[i]];
  }
  return out;
}

CellMembers membersOf(const CellAssignment& assignment) {
  // A counting sort: each range counts its points per cell, the counts give
  // every range its place within each cell (range by range, so ids ascend
  // within a cell as in one pass), and the ranges fill their places side by
  // side.
  const std::size_t n = assignment.cell_of_point.size();
  const std::size_t cells = assignment.cells();
  const std::size_t ranges = rangesFor(n);
  const std::vector<std::size_t> start = rangeStarts(n, ranges);
  std::vector<std::vector<std::uint32_t>> fill(ranges, std::vector<std::uint32_t>(cells, 0));
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t k) {
    for (std::size_t i = start[k]; i < start[k + 1]; ++i) ++fill[k][assignment.cell_of_point[i]];
  });
  CellMembers out;
  out.begin.assign(cells + 1, 0);
  std::uint32_t offset = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    out.begin[c] = offset;
    for (std::size_t k = 0; k < ranges; ++k) {
      const std::uint32_t count = fill[k][c];
      fill[k][c] = offset;
      offset += count;
    }
  }
  out.begin[cells] = offset;
  out.ids.resize(n);
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t k) {
    std::vector<std::uint32_t>& next = fill[k];
    for (std::size_t i = start[k]; i < start[k + 1]; ++i) {
      out.ids[next[assignment.cell_of_point[i]]++] = static_cast<std::uint32_t>(i);
    }
  });
  return out;
}

}  // namespace hba::voxel
