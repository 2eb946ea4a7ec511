#include "hba/pipeline/memory_estimate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hba/core/error.hpp"
#include "hba/pipeline/window_size.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/voxel/downsample.hpp"
#include "pyramid/window_batches.hpp"
#include "refine/group_refinement.hpp"

namespace hba::pipeline {
namespace {

// Calibrated on peak RSS (docs/pyramid.md, "Memory": hku1, nclt and
// simulated sequences of 200 to 1000 frames, one layer and the defaults),
// each rounded up, so that the estimate stays a little above the peak.
constexpr double kBaseBytes = 40.0 * (1 << 20);  // libraries, thread pools, poses, the pose graph
// A cloud held: float xyz and intensity.
constexpr double kCloudBytesPerPoint = 16.0;
// A BA: the clouds it holds, their planes, clusters and point lists, and
// what the allocator keeps of their earlier rounds.
constexpr double kBaBytesPerPoint = 60.0;
// (6K)^2 doubles at once for K frames: the Hessian, its damped copy and
// factor in LM, then the Hessian, the gauge-fixed copy, its eigenvectors
// and the products of the covariance the pose-graph factors come from
// (seven counted in the code; nine measured where the allocator keeps
// freed ones, below its 32 MiB mmap threshold).
constexpr double kBaDenseCopies = 9.0;
// The refinement (or with one layer the self-check): clouds, the plane
// map, per-plane factors and observations (44-69 bytes a point measured:
// more where more frames see each plane, as in simulated sequences).
constexpr double kRefineBytesPerPoint = 80.0;
// The groups' dense solve: the system, its damped copy and the factor.
constexpr double kGroupDenseCopies = 3.0;

double denseBytes(std::size_t frames, double copies) {
  const double unknowns = 6.0 * static_cast<double>(frames);
  return copies * unknowns * unknowns * sizeof(double);
}

// Frames of each layer: layer 1 the scans, each next one a frame per window.
std::size_t topFrames(std::size_t frames, int layers, const HbaSettings& settings) {
  for (int layer = 1; layer < layers; ++layer)
    frames = pyramid::planWindows(frames, settings.window, settings.stride).size();
  return frames;
}

// Points the global BA holds. With one layer, the scans; above, keyframes:
// a window's plane points at the keyframe voxel, each frame in
// window / stride windows. Surfaces: points scale with 1 / voxel^2.
double topPoints(double scan_points, int layers, const HbaSettings& settings) {
  if (layers <= 1) return scan_points;
  const double kept = settings.scan_voxel > 0.0 ? settings.scan_voxel / keyframeVoxel(settings, layers) : 1.0;
  const double overlap = static_cast<double>(settings.window) / settings.stride;
  return scan_points * std::min(1.0, overlap * kept * kept);
}

std::string millions(double points) { return fmt::format("{:.1f} M points", points / 1e6); }

}  // namespace

std::vector<std::size_t> spreadSample(std::size_t n, std::size_t samples) {
  const std::size_t count = std::min(n, samples);
  std::vector<std::size_t> indices;
  indices.reserve(count);
  for (std::size_t k = 0; k < count; ++k) indices.push_back(count == 1 ? 0 : k * (n - 1) / (count - 1));
  return indices;
}

ScanSample readScanSample(const io::ScanSource& scans, double scan_voxel, std::size_t samples) {
  ScanSample out;
  if (scans.size() == 0 || samples == 0) return out;
  out.indices = spreadSample(scans.size(), samples);
  for (const std::size_t i : out.indices) out.clouds.push_back(voxel::downsample(scans.load(i), scan_voxel));
  return out;
}

ScanDensity densityOf(const io::ScanSource& scans, const ScanSample& sample, const HbaSettings& settings) {
  ScanDensity density;
  const std::size_t n = scans.size();
  const std::size_t count = sample.clouds.size();
  if (n == 0 || count == 0) return density;
  double points = 0.0, refine_points = 0.0, sampled_hint = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const PointCloud& scan = sample.clouds[k];
    points += static_cast<double>(scan.size());
    refine_points += static_cast<double>(settings.refine_scan_voxel > 0.0
                                             ? voxel::downsample(scan, settings.refine_scan_voxel, 2).size()
                                             : scan.size());
    sampled_hint += scans.sizeHint(sample.indices[k]);
  }
  // Per scan on average, the sample's points per unit of size hint times
  // the average hint of all scans.
  double all_hint = 0.0;
  for (std::size_t i = 0; i < n; ++i) all_hint += scans.sizeHint(i);
  const double scale = sampled_hint > 0.0 ? all_hint / static_cast<double>(n) / sampled_hint
                                          : 1.0 / static_cast<double>(count);
  density.sampled = count;
  density.points = points * scale;
  density.sampled_points = points / static_cast<double>(count);
  density.refine_points = refine_points * scale;
  return density;
}

ScanDensity sampleScanDensity(const io::ScanSource& scans, const HbaSettings& settings, std::size_t samples) {
  return densityOf(scans, readScanSample(scans, settings.scan_voxel, samples), settings);
}

std::string stageName(Stage stage) {
  switch (stage) {
    case Stage::Windows:
      return "windows";
    case Stage::GlobalBa:
      return "global BA";
    case Stage::Refinement:
      return "refinement";
    case Stage::SelfCheck:
      return "self-check";
    case Stage::RefinementGroups:
      return "refinement groups";
  }
  return "?";
}

const StageMemory& MemoryEstimate::largest() const {
  if (stages.empty()) throw Error("memory estimate: no stages");
  return *std::max_element(stages.begin(), stages.end(),
                           [](const StageMemory& a, const StageMemory& b) { return a.bytes < b.bytes; });
}

MemoryEstimate estimateMemory(std::size_t frames, const ScanDensity& density, const HbaSettings& settings) {
  if (settings.window < 1 || settings.stride < 1)
    throw Error("memory estimate: the window is automatic; plan the run first (plan.hpp)");
  MemoryEstimate estimate;
  estimate.layers = pyramid::layerCount(frames, settings);
  estimate.top_frames = topFrames(frames, estimate.layers, settings);
  const double scan_points = density.points * static_cast<double>(frames);

  // Below the top, windows run a batch at a time (window_batches.hpp), one
  // per thread at once; their clouds are all a batch holds.
  if (estimate.layers > 1) {
    const auto threads = static_cast<std::size_t>(std::max(settings.threads, 1));
    const auto window = static_cast<std::size_t>(settings.window);
    const std::size_t held = std::min(
        frames, pyramid::windowsPerBatch(true, threads) * static_cast<std::size_t>(settings.stride) + window);
    const double window_points = density.points * static_cast<double>(window);
    estimate.stages.push_back(
        {Stage::Windows,
         kBaseBytes + kCloudBytesPerPoint * density.points * static_cast<double>(held) +
             static_cast<double>(threads) *
                 (kBaBytesPerPoint * window_points + denseBytes(window, kBaDenseCopies)),
         fmt::format("{} windows of {} frames at once, {} scans held", threads, window, held)});
  }

  const std::size_t k = estimate.top_frames;
  const double top_points = topPoints(scan_points, estimate.layers, settings);
  estimate.stages.push_back(
      {Stage::GlobalBa, kBaseBytes + kBaBytesPerPoint * top_points + denseBytes(k, kBaDenseCopies),
       fmt::format("{} frames: a dense {} x {} system and {}", k, 6 * k, 6 * k, millions(top_points))});

  const bool refines = estimate.layers > 1 && settings.refine;
  const double refine_all = density.refine_points * static_cast<double>(frames);
  const double block = std::min(refine_all, static_cast<double>(settings.refine_max_points));
  estimate.stages.push_back({refines ? Stage::Refinement : Stage::SelfCheck,
                             kBaseBytes + kRefineBytesPerPoint * block, millions(block) + " held at once"});

  // Beyond one block, rigid groups of frames, solved densely.
  if (refines && settings.refine_groups && refine_all > static_cast<double>(settings.refine_max_points)) {
    const std::size_t size = refine::groupSize(frames, settings.group_max_count, settings.group_min_frames);
    const std::size_t groups = (frames + size - 1) / size;
    const double ratio = settings.refine_scan_voxel > 0.0 && settings.group_voxel > settings.refine_scan_voxel
                             ? settings.refine_scan_voxel / settings.group_voxel
                             : 1.0;
    const double group_points = refine_all * ratio * ratio;
    estimate.stages.push_back(
        {Stage::RefinementGroups,
         kBaseBytes + kRefineBytesPerPoint * group_points + denseBytes(groups, kGroupDenseCopies),
         fmt::format("{} groups: a dense {} x {} system and {}", groups, 6 * groups, 6 * groups,
                     millions(group_points))});
  }
  return estimate;
}

}  // namespace hba::pipeline
