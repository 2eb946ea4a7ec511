// Voxel downsampling and adaptive plane extraction, per million points.
#include <benchmark/benchmark.h>

#include <random>

#include "hba/voxel/downsample.hpp"
#include "hba/voxel/plane_map.hpp"
#include "synthetic_window.hpp"

namespace hba::voxel {
namespace {

void BM_Downsample(benchmark::State& state) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-25.f, 25.f);
  PointCloud cloud;
  for (int i = 0; i < 1'000'000; ++i) cloud.add(Vec3f(u(rng), u(rng), 0.2f * u(rng)));
  for (auto _ : state) benchmark::DoNotOptimize(downsample(cloud, 0.1));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cloud.size()));
}
BENCHMARK(BM_Downsample)->Unit(benchmark::kMillisecond)->UseRealTime();

// 10 scans x ~100k points of plane patches, placed with perturbed poses (so
// voxels mix frames as in a real window).
void BM_ExtractPlanes(benchmark::State& state) {
  test::SyntheticWindowSpec spec;
  spec.frames = 10;
  spec.points_per_patch = 11'112;  // 9 patches: ~100k points per scan
  spec.noise_sigma = 0.02;
  const auto window = test::makeSyntheticWindow(spec);
  PlaneSettings settings;
  settings.voxel_size = static_cast<double>(state.range(0));
  std::int64_t points = 0;
  for (const auto& scan : window.scans) points += static_cast<std::int64_t>(scan.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(extractPlanes(window.scanPointers(), window.initial, settings));
  }
  state.SetItemsProcessed(state.iterations() * points);
}
BENCHMARK(BM_ExtractPlanes)->Arg(8)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hba::voxel
