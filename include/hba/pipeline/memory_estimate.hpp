#pragma once
// What a run of `hba optimize` holds at its peak, estimated before the run
// reads more than a few scans: a run that cannot fit is refused at the
// start, with the figures and the settings that would fit, instead of being
// killed by the kernel without a word (docs/pyramid.md, "Memory").
//
// The model (calibrated by peak RSS, docs/pyramid.md): each stage holds
// the process's base, some bytes per point it works on, and, for the BAs
// solved densely (the global BA, the rigid groups), a few (6K)^2 matrices
// of doubles for K frames. The global BA's grow with the square of its
// frames: `--layers 1` over thousands of scans needs tens of GB.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/io/scan_source.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pipeline {

// Points a scan holds as the run works on it, from a few scans read.
struct ScanDensity {
  std::size_t sampled = 0;     // scans read
  double points = 0.0;         // per scan, at settings.scan_voxel (the windows' and the global BA's)
  double refine_points = 0.0;  // per scan, at the refinement's density
  // Per scan read, unweighted: the same for the same scans in any container
  // (a bag's compressed message sizes weigh them otherwise).
  double sampled_points = 0.0;
};

// The indices of up to `samples` scans spread evenly over `n`, first and
// last included: the scans a run reads to learn the sequence's density.
std::vector<std::size_t> spreadSample(std::size_t n, std::size_t samples);

// Up to `samples` scans spread over a sequence (spreadSample), read as
// given (sensor frame, full density) and downsampled at the scan voxel, as
// the run's windows see them: what the plan learns the density from.
struct ScanSample {
  std::vector<std::size_t> indices;
  std::vector<PointCloud> clouds;
};
ScanSample readScanSample(const io::ScanSource& scans, double scan_voxel, std::size_t samples = 16);

// The sequence's density from such a sample. Scans whose source tells
// their size (a file's bytes) are weighted by it, so that a sequence of
// uneven scans is counted by all of them.
ScanDensity densityOf(const io::ScanSource& scans, const ScanSample& sample, const HbaSettings& settings);

// readScanSample at settings.scan_voxel, then densityOf.
ScanDensity sampleScanDensity(const io::ScanSource& scans, const HbaSettings& settings,
                              std::size_t samples = 16);

enum class Stage {
  Windows,           // the windows below the top layer, a batch at a time
  GlobalBa,          // the top layer's one BA over all its frames
  Refinement,        // the final sparse BA, a block of scans at a time
  SelfCheck,         // with one layer, the self-check alone (no refinement)
  RefinementGroups,  // beyond one block: rigid groups of frames, solved densely
};
// "global BA", "refinement", ...
std::string stageName(Stage stage);

// One stage's peak: the whole process while it runs.
struct StageMemory {
  Stage stage = Stage::GlobalBa;
  double bytes = 0.0;  // at its peak
  std::string detail;  // what it is made of, for messages
};

struct MemoryEstimate {
  int layers = 0;
  std::size_t top_frames = 0;  // frames of the global BA (the top layer's)
  std::vector<StageMemory> stages;
  // The stage of the run's peak, and that peak.
  const StageMemory& largest() const;
  double peakBytes() const { return largest().bytes; }
};

// The estimate for `frames` scans of `density` under `settings`: the
// window and stride worked out (planRun does it; an automatic window throws),
// the layer count resolved as the run resolves it, settings.threads windows
// at once (0 = one).
MemoryEstimate estimateMemory(std::size_t frames, const ScanDensity& density, const HbaSettings& settings);

}  // namespace hba::pipeline
