// Time of verifyLoop per pair on a simulated city block (scans simulated and
// downsampled to 0.1 m before timing): the plane BA alone (exact guess), and
// with a +-5 m, +-10 deg bird's-eye search from a guess 3 m and 7 deg off.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "hba/closure/loop_check.hpp"
#include "hba/core/lie.hpp"
#include "simulated_scans.hpp"

namespace {
using namespace hba;

struct Drive {
  sim::Simulation simulation;
  std::unique_ptr<closure::test::LazySimulatedScans> scans;
};

const Drive& driveFor(sim::SensorModel model) {
  static std::map<sim::SensorModel, Drive> cache;
  auto it = cache.find(model);
  if (it == cache.end()) {
    it = cache.emplace(model, Drive{sim::prepareSimulation(closure::test::revisitingDrive(model)), nullptr})
             .first;
    it->second.scans = std::make_unique<closure::test::LazySimulatedScans>(it->second.simulation, 0.1);
  }
  return it->second;
}

void BM_VerifyLoop(benchmark::State& state) {
  const auto model = static_cast<sim::SensorModel>(state.range(0));
  const bool search = state.range(1) != 0;
  const Drive& drive = driveFor(model);
  const std::size_t from = 10;
  const std::size_t to = from + closure::test::kLap;
  const Pose truth = relative(drive.simulation.truth.poses[from], drive.simulation.truth.poses[to]);
  closure::LoopCheckSettings settings;
  closure::LoopPair pair{from, to, truth};
  if (search) {
    settings.search_radius_m = 5.0;
    settings.search_yaw_deg = 10.0;
    pair.relative = Pose(so3Exp(Vec3(0, 0, 7.0 * M_PI / 180.0)), Vec3(3.0, -2.0, 0.0)) * truth;
  }
  closure::verifyLoop(*drive.scans, drive.simulation.initial, pair, settings);  // simulates the scans
  std::size_t planes = 0;
  bool accepted = true;
  for (auto _ : state) {
    const closure::LoopCheck check =
        closure::verifyLoop(*drive.scans, drive.simulation.initial, pair, settings);
    planes = check.shared_planes;
    accepted = accepted && check.accepted;
  }
  state.counters["shared_planes"] = static_cast<double>(planes);
  state.counters["accepted"] = accepted ? 1.0 : 0.0;
  state.SetLabel(toString(model) + (search ? " search" : " exact"));
}

BENCHMARK(BM_VerifyLoop)
    ->ArgsProduct({{static_cast<int>(sim::SensorModel::Vlp16), static_cast<int>(sim::SensorModel::Hdl32)},
                   {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
