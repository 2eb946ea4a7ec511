// Simulation speed: frames per second of each sensor preset on the default
// city-block world, one frame per iteration on one thread, and a batch of
// frames over all cores (as `hba simulate` runs them).
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include <map>

#include "hba/sim/simulation.hpp"

namespace {
using namespace hba::sim;

const Simulation& simulationFor(SensorModel model) {
  static std::map<SensorModel, Simulation> cache;
  auto it = cache.find(model);
  if (it == cache.end()) {
    SimulationConfig config;
    config.seed = 1;
    config.trajectory.frames = 300;
    config.sensor = sensorPreset(model);
    it = cache.emplace(model, prepareSimulation(config)).first;
  }
  return it->second;
}

void BM_SimulateFrame(benchmark::State& state) {
  const auto model = static_cast<SensorModel>(state.range(0));
  const Simulation& simulation = simulationFor(model);
  std::size_t frame = 0, points = 0;
  for (auto _ : state) {
    const auto cloud = simulateFrame(simulation, frame);
    points += cloud.size();
    benchmark::DoNotOptimize(cloud.points.data());
    frame = (frame + 37) % simulation.truth.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));  // frames/s
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * simulation.config.sensor.raysPerFrame()),
                         benchmark::Counter::kIsRate);
  state.counters["points/frame"] = static_cast<double>(points) / state.iterations();
  state.SetLabel(hba::toString(model));
}

void BM_SimulateFramesAllCores(benchmark::State& state) {
  const auto model = static_cast<SensorModel>(state.range(0));
  const Simulation& simulation = simulationFor(model);
  constexpr std::size_t kBatch = 20;
  for (auto _ : state) {
    tbb::parallel_for(std::size_t{0}, kBatch, [&](std::size_t k) {
      const auto cloud = simulateFrame(simulation, k * 13);
      benchmark::DoNotOptimize(cloud.points.data());
    });
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetLabel(hba::toString(model));
}

void BM_BuildWorld(benchmark::State& state) {
  SimulationConfig config;
  config.trajectory.frames = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    const Simulation simulation = prepareSimulation(config);
    benchmark::DoNotOptimize(simulation.world.triangles().data());
  }
}

void allSensors(benchmark::internal::Benchmark* b) {
  for (SensorModel m :
       {SensorModel::Vlp16, SensorModel::Hdl32, SensorModel::Hdl64, SensorModel::Os128, SensorModel::Livox}) {
    b->Arg(static_cast<int>(m));
  }
}

BENCHMARK(BM_SimulateFrame)->Apply(allSensors)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateFramesAllCores)->Apply(allSensors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BuildWorld)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
