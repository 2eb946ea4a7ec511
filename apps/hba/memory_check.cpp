#include "memory_check.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <optional>
#include <string>

#include "core/available_memory.hpp"
#include "hba/core/error.hpp"
#include "hba/pipeline/memory_estimate.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "pipeline/report_json.hpp"

namespace hba::cli::optimize {
namespace {
using pipeline::MemoryEstimate;
using pipeline::Stage;

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

// A change of `settings` (the first of a few, each smaller) whose run fits
// in `available` bytes, said for the refusal; empty when none does.
std::string fittingChange(std::size_t frames, const pipeline::ScanDensity& density,
                          const HbaSettings& settings, Stage stage, double available) {
  auto peak = [&](const HbaSettings& changed) {
    return pipeline::estimateMemory(frames, density, changed).peakBytes();
  };
  HbaSettings changed = settings;
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

nlohmann::json toJson(const MemoryEstimate& estimate, const pipeline::ScanDensity& density,
                      const std::optional<AvailableMemory>& available) {
  nlohmann::json json = pipeline::memoryEstimateJson(estimate, density);
  if (available) {
    json["available_mib"] = mib(static_cast<double>(available->bytes));
    json["available_from"] = available->source;
  }
  return json;
}

}  // namespace

nlohmann::json checkMemory(const pipeline::Plan& plan, bool ignore) {
  const pipeline::ScanDensity& density = plan.density;
  const HbaSettings& settings = plan.settings;
  const MemoryEstimate& estimate = plan.memory;
  const std::optional<AvailableMemory> available = availableMemory();
  const pipeline::StageMemory& peak = estimate.largest();
  std::string stages;
  for (const pipeline::StageMemory& s : estimate.stages)
    stages +=
        fmt::format("{}{} {}", stages.empty() ? "" : ", ", pipeline::stageName(s.stage), humanBytes(s.bytes));
  spdlog::debug("memory estimate: peak about {} in the {} ({}); by stage: {}; available: {}",
                humanBytes(peak.bytes), pipeline::stageName(peak.stage), peak.detail, stages,
                available ? humanBytes(static_cast<double>(available->bytes)) + " (" + available->source + ")"
                          : "unknown");
  const nlohmann::json json = toJson(estimate, density, available);
  if (!available || peak.bytes <= static_cast<double>(available->bytes)) return json;

  const double room = static_cast<double>(available->bytes);
  const std::string change = fittingChange(plan.frames, density, settings, peak.stage, room);
  const std::string message = fmt::format(
      "not enough memory: this run's {} ({}) needs about {}, and {} are available ({}); {}",
      pipeline::stageName(peak.stage), peak.detail, humanBytes(peak.bytes), humanBytes(room),
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
