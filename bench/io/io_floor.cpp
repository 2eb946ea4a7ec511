// io_floor DIR [--voxel 0.1] [-j N]: the I/O floor of `hba optimize`, the
// time to read and voxel-downsample every scan once with the optimizer's own
// calls (io::DatasetScanSource, then voxel::downsample), in parallel. Prints
// one JSON object; the benchmark harness (scripts/bench) divides optimize's
// total by seconds_wall.
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/stopwatch.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/voxel/downsample.hpp"

namespace {

using hba::Clock;
using hba::secondsSince;

struct FloorTotals {
  std::size_t scans = 0;
  std::size_t points_read = 0;
  std::size_t points_kept = 0;
  double seconds_read = 0.0;        // summed over threads
  double seconds_downsample = 0.0;  // summed over threads

  FloorTotals& operator+=(const FloorTotals& other) {
    scans += other.scans;
    points_read += other.points_read;
    points_kept += other.points_kept;
    seconds_read += other.seconds_read;
    seconds_downsample += other.seconds_downsample;
    return *this;
  }
};

FloorTotals readAndDownsample(const hba::io::ScanSource& scans, std::size_t i, double voxel) {
  FloorTotals totals;
  const auto start = Clock::now();
  const hba::PointCloud scan = scans.load(i);
  totals.seconds_read = secondsSince(start);
  const auto downsampled = Clock::now();
  totals.points_kept = hba::voxel::downsample(scan, voxel).size();
  totals.seconds_downsample = secondsSince(downsampled);
  totals.points_read = scan.size();
  totals.scans = 1;
  return totals;
}

FloorTotals readEveryScan(const hba::io::ScanSource& scans, double voxel) {
  tbb::combinable<FloorTotals> per_thread;
  // One scan per task, as the optimizer loads them.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, scans.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        per_thread.local() += readAndDownsample(scans, i, voxel);
                      }
                    });
  FloorTotals totals;
  per_thread.combine_each([&](const FloorTotals& part) { totals += part; });
  return totals;
}

void run(const std::string& dir, double voxel) {
  const auto start = Clock::now();
  const hba::io::Dataset dataset = hba::io::Dataset::open(dir);
  const FloorTotals totals = readEveryScan(hba::io::DatasetScanSource(dataset), voxel);
  const nlohmann::json report = {
      {"dataset", dir},
      {"voxel", voxel},
      {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)},
      {"scans", totals.scans},
      {"points_read", totals.points_read},
      {"points_kept", totals.points_kept},
      {"seconds_wall", secondsSince(start)},
      {"seconds_read", totals.seconds_read},
      {"seconds_downsample", totals.seconds_downsample}};
  std::cout << report.dump(2) << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time to read and voxel-downsample every scan of a dataset once (JSON on stdout)"};
  std::string dir;
  double voxel = 0.1;
  int threads = 0;
  app.add_option("DIR", dir, "Dataset folder (any layout hba reads)")->required();
  app.add_option("--voxel", voxel, "Downsampling voxel (m), as optimize's --downsample-scans")
      ->capture_default_str();
  app.add_option("-j,--threads", threads, "Worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);

  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                         static_cast<std::size_t>(threads));
  }
  try {
    run(dir, voxel);
  } catch (const hba::Error& e) {
    std::cerr << "io_floor: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
