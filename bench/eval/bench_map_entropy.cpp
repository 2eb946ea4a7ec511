// Mean map entropy on the real hku1 map (merged once, outside the timing).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "hba/eval/map_entropy.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_source.hpp"

namespace {

const std::filesystem::path kHku1 = HBA_BENCH_SHARED_DATA "/hku1";

hba::PointCloud hku1Map() {
  static const hba::PointCloud map = [] {
    const auto dataset = hba::io::Dataset::open(kHku1);
    const hba::io::DatasetScanSource scans(dataset);
    return hba::eval::buildMergedMap(scans, dataset.trajectory().poses, hba::eval::MapSettings{});
  }();
  return map;
}

void BM_MergeHku1(benchmark::State& state) {
  if (!std::filesystem::exists(kHku1)) return state.SkipWithError("no hku1 data");
  const auto dataset = hba::io::Dataset::open(kHku1);
  const hba::io::DatasetScanSource scans(dataset);
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        hba::eval::buildMergedMap(scans, dataset.trajectory().poses, hba::eval::MapSettings{}));
  }
}
BENCHMARK(BM_MergeHku1)->Unit(benchmark::kMillisecond);

void BM_MmeHku1(benchmark::State& state) {
  if (!std::filesystem::exists(kHku1)) return state.SkipWithError("no hku1 data");
  const hba::PointCloud map = hku1Map();
  for (auto _ : state) benchmark::DoNotOptimize(hba::eval::meanMapEntropy(map));
  state.counters["points"] = static_cast<double>(map.size());
}
BENCHMARK(BM_MmeHku1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
