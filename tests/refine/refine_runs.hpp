#pragma once
// The last stage run as the pipeline runs it after a three-layer pyramid,
// its outcome written into `report` where the pipeline writes it.
#include <vector>

#include "hba/pipeline/hierarchical_ba.hpp"
#include "refine/refinement.hpp"
#include "settings/refine_settings.hpp"

namespace hba::refine {

inline std::vector<Pose> refineAs3Layers(const io::ScanSource& scans, const std::vector<Pose>& initial,
                                         const std::vector<Pose>& hierarchy, const HbaSettings& settings,
                                         pipeline::HbaReport& report) {
  HierarchyFacts facts;
  facts.layers = 3;
  RefineOutcome out =
      refineAndCheck(scans, initial, hierarchy, facts, {}, settings::refineSettingsOf(settings));
  report.consistency = out.consistency;
  report.refinement = out.refinement;
  report.warnings = out.notes.warnings;
  return out.poses;
}

}  // namespace hba::refine
