#pragma once
// The last stage run as the pipeline runs it after a three-layer pyramid,
// its outcome written into `report` where the pipeline writes it.
#include <vector>

#include "hba/pyramid/hierarchical_ba.hpp"
#include "pyramid/refine_settings.hpp"
#include "refine/refinement.hpp"

namespace hba::refine {

inline std::vector<Pose> refineAs3Layers(const io::ScanSource& scans, const std::vector<Pose>& initial,
                                         const std::vector<Pose>& hierarchy,
                                         const pyramid::HbaSettings& settings, pyramid::HbaReport& report) {
  HierarchyFacts facts;
  facts.layers = 3;
  RefineOutcome out =
      refineAndCheck(scans, initial, hierarchy, facts, {}, pyramid::refineSettingsOf(settings));
  report.consistency = out.consistency;
  report.refinement = out.refinement;
  report.warnings = out.notes.warnings;
  return out.poses;
}

}  // namespace hba::refine
