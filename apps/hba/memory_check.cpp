#include "memory_check.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <optional>
#include <string>

#include "core/available_memory.hpp"
#include "hba/core/error.hpp"
#include "hba/pyramid/memory_estimate.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/pyramid/window_size.hpp"

namespace hba::cli::optimize {
namespace {
using pyramid::MemoryEstimate;
using pyramid::Stage;

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

// A change of `settings` (the first of a few, each smaller) whose run fits
// in `available` bytes, said for the refusal; empty when none does.
std::string fittingChange(std::size_t frames, const pyramid::ScanDensity& density,
                          const pyramid::HbaSettings& settings, Stage stage, double available) {
  auto peak = [&](const pyramid::HbaSettings& changed) {
    return pyramid::estimateMemory(frames, density, changed).peakBytes();
  };
  pyramid::HbaSettings changed = settings;
  switch (stage) {
    case Stage::GlobalBa:
      for (int layers = pyramid::layerCount(frames, settings) + 1;
           layers <= pyramid::maxLayerCount(frames, settings.window, settings.stride); ++layers) {
        changed.layers = layers;
        if (peak(changed) <= available)
          return fmt::format("use more layers: --layers {} needs about {}", layers,
                             humanBytes(peak(changed)));
      }
      break;
    case Stage::Windows:
      for (changed.threads = settings.threads / 2; changed.threads >= 1; changed.threads /= 2) {
        if (peak(changed) <= available)
          return fmt::format("run fewer windows at once: -j {} needs about {}", changed.threads,
                             humanBytes(peak(changed)));
      }
      break;
    case Stage::Refinement:
    case Stage::SelfCheck:
      for (changed.refine_max_points = settings.refine_max_points / 2; changed.refine_max_points >= 500'000;
           changed.refine_max_points /= 2) {
        if (peak(changed) <= available)
          return fmt::format(
              "hold fewer points at once: 'refine_max_points: {}' in a --config file needs about {}",
              changed.refine_max_points, humanBytes(peak(changed)));
      }
      break;
    case Stage::RefinementGroups:
      for (changed.group_max_count = settings.group_max_count / 2; changed.group_max_count >= 50;
           changed.group_max_count /= 2) {
        if (peak(changed) <= available)
          return fmt::format("use fewer groups: 'group_max_count: {}' in a --config file needs about {}",
                             changed.group_max_count, humanBytes(peak(changed)));
      }
      break;
  }
  return "";
}

nlohmann::json toJson(const MemoryEstimate& estimate, const pyramid::ScanDensity& density,
                      const std::optional<AvailableMemory>& available) {
  nlohmann::json stages = nlohmann::json::array();
  for (const pyramid::StageMemory& s : estimate.stages) {
    stages.push_back({{"stage", pyramid::stageName(s.stage)}, {"mib", mib(s.bytes)}, {"detail", s.detail}});
  }
  nlohmann::json json = {{"peak_mib", mib(estimate.peakBytes())},
                         {"peak_stage", pyramid::stageName(estimate.largest().stage)},
                         {"stages", stages},
                         {"scans_sampled", density.sampled},
                         {"points_per_scan", density.points}};
  if (available) {
    json["available_mib"] = mib(static_cast<double>(available->bytes));
    json["available_from"] = available->source;
  }
  return json;
}

}  // namespace

nlohmann::json checkMemory(const io::ScanSource& scans, const pyramid::HbaSettings& given, bool ignore) {
  const pyramid::ScanDensity density = pyramid::sampleScanDensity(scans, given);
  // The windows the run will use (an automatic window from the same density).
  const pyramid::HbaSettings settings =
      pyramid::withWindowSize(given, pyramid::chooseWindowSize(given, density.sampled_points));
  const MemoryEstimate estimate = pyramid::estimateMemory(scans.size(), density, settings);
  const std::optional<AvailableMemory> available = availableMemory();
  const pyramid::StageMemory& peak = estimate.largest();
  std::string stages;
  for (const pyramid::StageMemory& s : estimate.stages)
    stages +=
        fmt::format("{}{} {}", stages.empty() ? "" : ", ", pyramid::stageName(s.stage), humanBytes(s.bytes));
  spdlog::debug("memory estimate: peak about {} in the {} ({}); by stage: {}; available: {}",
                humanBytes(peak.bytes), pyramid::stageName(peak.stage), peak.detail, stages,
                available ? humanBytes(static_cast<double>(available->bytes)) + " (" + available->source + ")"
                          : "unknown");
  const nlohmann::json json = toJson(estimate, density, available);
  if (!available || peak.bytes <= static_cast<double>(available->bytes)) return json;

  const double room = static_cast<double>(available->bytes);
  const std::string change = fittingChange(scans.size(), density, settings, peak.stage, room);
  const std::string message = fmt::format(
      "not enough memory: this run's {} ({}) needs about {}, and {} are available ({}); {}",
      pyramid::stageName(peak.stage), peak.detail, humanBytes(peak.bytes), humanBytes(room),
      available->source,
      change.empty() ? "no smaller setting tried fits: a coarser --downsample-scans holds fewer points"
                     : change);
  if (ignore) {
    spdlog::warn("{} (going on: --no-memory-check)", message);
    return json;
  }
  throw Error(message + "; or run anyway with --no-memory-check");
}

}  // namespace hba::cli::optimize
