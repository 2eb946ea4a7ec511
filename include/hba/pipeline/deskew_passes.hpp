#pragma once
// The method on a dataset, with raw sweeps deskewed again by what it found
// (docs/recordings.md, "Deskewing"). Sweeps whose points carry times are
// first deskewed by the input's motion; the run corrects that motion, so each
// further pass deskews them by the poses the last one found and runs the
// method again from there. `hba optimize --deskew-passes N` and
// hba.optimize(dataset, deskew_passes=N) make this one call.
#include <vector>

#include <nlohmann/json.hpp>

#include "hba/dist/group.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"

namespace hba::pipeline {

struct DeskewPass {
  double largest_update_against_input_m = 0.0;
  double seconds = 0.0;
};

struct DatasetRun {
  // The last pass's result; its report speaks of the whole run: the largest
  // update against the input, the time of every pass.
  pipeline::HbaResult result;
  std::vector<DeskewPass> earlier_passes;  // empty: one pass
};

// runHierarchicalBa on `scans` (read through `dataset`, e.g. an
// io::DatasetScanSource of it, so that deskewBy reaches them) from
// `initial`, `passes` times in all when the dataset has point times, else
// once. `dataset` is left deskewed by the last pass's start poses.
// Every pass runs by `plan` (planRun over `scans`, before the first).
DatasetRun runWithDeskewPasses(io::Dataset& dataset, const io::ScanSource& scans,
                               const std::vector<Pose>& initial, const Plan& plan,
                               const pipeline::ClosureInputs& closures, int passes,
                               const dist::Group& group = dist::singleProcess());

// report.json's "deskew": the point times read and the passes made; null
// for scans without point times.
nlohmann::json deskewReport(const io::Dataset& dataset, const DatasetRun& run);

}  // namespace hba::pipeline
