// The pieces of one bottom-layer window on real scans: ten consecutive scans
// of the sequence in $HBA_BENCH_WINDOW (any folder `hba optimize` reads),
// downsampled as layer 1 does (0.1 m), at their input poses. Skipped when
// the variable is unset. Example:
//   HBA_BENCH_WINDOW=../shared/data/hku1 build/bin/bench_ba --benchmark_filter=RealWindow
// The RealBlock benchmarks take a refinement block instead: the first
// $HBA_BENCH_BLOCK_SCANS (300) scans at the refinement's 0.2 m.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "hba/ba/association.hpp"
#include "hba/ba/lm_solver.hpp"
#include "hba/io/dataset.hpp"
#include "hba/voxel/downsample.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::ba {
namespace {

struct RealWindow {
  PointCloud raw;  // the first scan as read
  std::vector<PointCloud> scans;
  std::vector<Pose> poses;
  std::size_t points = 0;
  std::vector<const PointCloud*> pointers() const {
    std::vector<const PointCloud*> out;
    for (const PointCloud& scan : scans) out.push_back(&scan);
    return out;
  }
};

// Loaded once: the benchmarks time the window's work, not the disk.
// Scans [first, end) of `data` (clamped to it) at `voxel`, with their poses.
RealWindow readScans(const io::Dataset& data, std::size_t first, std::size_t end, double voxel,
                     std::size_t points_per_cell) {
  RealWindow w;
  for (std::size_t i = first; i < std::min(data.size(), end); ++i) {
    w.scans.push_back(voxel::downsample(data.loadScan(i), voxel, points_per_cell));
    w.poses.push_back(data.trajectory().poses[i]);
    w.points += w.scans.back().size();
  }
  return w;
}

const std::optional<RealWindow>& realWindow() {
  static const std::optional<RealWindow> window = []() -> std::optional<RealWindow> {
    const char* dir = std::getenv("HBA_BENCH_WINDOW");
    if (dir == nullptr) return std::nullopt;
    const io::Dataset data = io::Dataset::open(dir);
    const std::size_t first = data.size() / 2;
    RealWindow w = readScans(data, first, first + 10, 0.1, 0);
    w.raw = data.loadScan(first);
    return w;
  }();
  return window;
}

// The first scans of the same sequence as a refinement block loads them.
const std::optional<RealWindow>& realBlock() {
  static const std::optional<RealWindow> block = []() -> std::optional<RealWindow> {
    const char* dir = std::getenv("HBA_BENCH_WINDOW");
    if (dir == nullptr) return std::nullopt;
    const char* count = std::getenv("HBA_BENCH_BLOCK_SCANS");
    return readScans(io::Dataset::open(dir), 0, count ? std::stoul(count) : 300, 0.2, 2);
  }();
  return block;
}

voxel::PlaneSettings planesAt(double voxel) {
  voxel::PlaneSettings settings;
  settings.voxel_size = voxel;
  return settings;
}

// A scan as read, downsampled as layer 1 loads it.
void BM_RealScanDownsample(benchmark::State& state) {
  const auto& w = realWindow();
  if (!w) return state.SkipWithError("HBA_BENCH_WINDOW is not set");
  for (auto _ : state) benchmark::DoNotOptimize(voxel::downsample(w->raw, 0.1));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(w->raw.size()));
}
BENCHMARK(BM_RealScanDownsample)->Unit(benchmark::kMillisecond);

void BM_RealWindowExtractPlanes(benchmark::State& state) {
  const auto& w = realWindow();
  if (!w) return state.SkipWithError("HBA_BENCH_WINDOW is not set");
  const auto settings = planesAt(static_cast<double>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(voxel::extractPlanes(w->pointers(), w->poses, settings));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(w->points));
}
BENCHMARK(BM_RealWindowExtractPlanes)->Arg(4)->Arg(1)->Unit(benchmark::kMillisecond);

// A refinement block's association (its points at 1 m voxels).
void BM_RealBlockExtractPlanes(benchmark::State& state) {
  const auto& b = realBlock();
  if (!b) return state.SkipWithError("HBA_BENCH_WINDOW is not set");
  const auto settings = planesAt(1.0);
  for (auto _ : state) benchmark::DoNotOptimize(voxel::extractPlanes(b->pointers(), b->poses, settings));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(b->points));
}
BENCHMARK(BM_RealBlockExtractPlanes)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RealWindowAssociate(benchmark::State& state) {
  const auto& w = realWindow();
  if (!w) return state.SkipWithError("HBA_BENCH_WINDOW is not set");
  const auto settings = planesAt(1.0);
  for (auto _ : state) benchmark::DoNotOptimize(associate(w->pointers(), w->poses, settings, 0.05));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(w->points));
}
BENCHMARK(BM_RealWindowAssociate)->Unit(benchmark::kMillisecond);

void BM_RealWindowLinearize(benchmark::State& state) {
  const auto& w = realWindow();
  if (!w) return state.SkipWithError("HBA_BENCH_WINDOW is not set");
  const Association association = associate(w->pointers(), w->poses, planesAt(1.0), 0.05);
  for (auto _ : state) benchmark::DoNotOptimize(association.problem.linearize(w->poses));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(association.problem.numPlanes()));
}
BENCHMARK(BM_RealWindowLinearize)->Unit(benchmark::kMillisecond);

void BM_RealWindowCost(benchmark::State& state) {
  const auto& w = realWindow();
  if (!w) return state.SkipWithError("HBA_BENCH_WINDOW is not set");
  const Association association = associate(w->pointers(), w->poses, planesAt(1.0), 0.05);
  for (auto _ : state) benchmark::DoNotOptimize(association.problem.cost(w->poses));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(association.problem.numPlanes()));
}
BENCHMARK(BM_RealWindowCost)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hba::ba
