// Plane cost and derivative evaluation: one plane (cluster form vs the naive
// per-point form), a 10-scan window, and a top-layer-sized problem.
#include <benchmark/benchmark.h>

#include <numeric>
#include <random>

#include "hba/ba/plane_problem.hpp"
#include "hba/ba/window_ba.hpp"
#include "pointwise_plane_cost.hpp"
#include "random_planes.hpp"
#include "synthetic_window.hpp"

namespace hba::ba {
namespace {

std::vector<std::uint32_t> firstFrames(int count) {
  std::vector<std::uint32_t> frames(static_cast<std::size_t>(count));
  std::iota(frames.begin(), frames.end(), 0u);
  return frames;
}

// Args: frames seeing the plane, points per frame.
void BM_PlaneCostCluster(benchmark::State& state) {
  std::mt19937 rng(1);
  const int frames = static_cast<int>(state.range(0));
  const auto poses = test::randomPoses(rng, frames, 5.0);
  const auto plane =
      test::randomPlane(rng, poses, firstFrames(frames), static_cast<int>(state.range(1)), 0.02);
  const FrameTransforms transforms(poses);
  for (auto _ : state) benchmark::DoNotOptimize(planeCost(plane.observation, transforms));
}
BENCHMARK(BM_PlaneCostCluster)->Args({10, 100});

void BM_PlaneDerivativesCluster(benchmark::State& state) {
  std::mt19937 rng(1);
  const int frames = static_cast<int>(state.range(0));
  const auto poses = test::randomPoses(rng, frames, 5.0);
  const auto plane =
      test::randomPlane(rng, poses, firstFrames(frames), static_cast<int>(state.range(1)), 0.02);
  const FrameTransforms transforms(poses);
  for (auto _ : state) {
    const PlaneLinearization lin = linearizePlane(plane.observation, transforms);
    benchmark::DoNotOptimize(lin.denseHessian());
  }
}
BENCHMARK(BM_PlaneDerivativesCluster)->Args({2, 100})->Args({10, 100})->Args({10, 1000});

// The same cost, gradient and dense Hessian from every raw point.
void BM_PlaneDerivativesPointwise(benchmark::State& state) {
  std::mt19937 rng(1);
  const int frames = static_cast<int>(state.range(0));
  const auto poses = test::randomPoses(rng, frames, 5.0);
  const auto plane =
      test::randomPlane(rng, poses, firstFrames(frames), static_cast<int>(state.range(1)), 0.02);
  for (auto _ : state) {
    benchmark::DoNotOptimize(test::pointwisePlaneDerivatives(plane.sensor_points, poses));
  }
}
BENCHMARK(BM_PlaneDerivativesPointwise)->Args({2, 100})->Args({10, 100})->Args({10, 1000});

// A problem of `planes` planes over `frames` frames, each plane seen by
// `per_plane` consecutive frames.
PlaneProblem makeProblem(int frames, int planes, int per_plane, std::vector<Pose>& poses) {
  std::mt19937 rng(2);
  poses = test::randomPoses(rng, frames, 5.0);
  std::vector<PlaneObservation> observations;
  for (int p = 0; p < planes; ++p) {
    std::vector<std::uint32_t> seen;
    const int start = (p * 7) % (frames - per_plane + 1);
    for (int f = start; f < start + per_plane; ++f) seen.push_back(static_cast<std::uint32_t>(f));
    observations.push_back(test::randomPlane(rng, poses, seen, 20, 0.02).observation);
  }
  return PlaneProblem(std::move(observations), static_cast<std::size_t>(frames));
}

// Args: frames, planes, frames per plane.
void BM_ProblemLinearize(benchmark::State& state) {
  std::vector<Pose> poses;
  const PlaneProblem problem = makeProblem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                                           static_cast<int>(state.range(2)), poses);
  for (auto _ : state) benchmark::DoNotOptimize(problem.linearize(poses));
  state.SetItemsProcessed(state.iterations() * state.range(1));  // planes
}
BENCHMARK(BM_ProblemLinearize)
    ->Args({10, 400, 6})     // a local window
    ->Args({300, 3000, 10})  // a top layer
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_ProblemCost(benchmark::State& state) {
  std::vector<Pose> poses;
  const PlaneProblem problem = makeProblem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                                           static_cast<int>(state.range(2)), poses);
  for (auto _ : state) benchmark::DoNotOptimize(problem.cost(poses));
  state.SetItemsProcessed(state.iterations() * state.range(1));
}
BENCHMARK(BM_ProblemCost)->Args({10, 400, 6})->Unit(benchmark::kMicrosecond)->UseRealTime();

// The whole window BA (association rounds + LM) on the synthetic window.
void BM_OptimizeWindow(benchmark::State& state) {
  test::SyntheticWindowSpec spec;
  spec.frames = 10;
  spec.points_per_patch = static_cast<int>(state.range(0));
  spec.noise_sigma = 0.01;
  const auto window = test::makeSyntheticWindow(spec);
  const BaSettings settings = test::patchBaSettings();
  for (auto _ : state) {
    benchmark::DoNotOptimize(optimizeWindow(window.scanPointers(), window.initial, settings));
  }
}
BENCHMARK(BM_OptimizeWindow)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hba::ba
