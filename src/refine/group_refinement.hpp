#pragma once
// The refinement's coarse, whole-sequence half: consecutive frames tied
// into rigid groups, each group's scans merged, one plane BA places the
// groups (docs/pyramid.md, "Long sequences").
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "refinement.hpp"

namespace hba::refine {

std::size_t groupSize(std::size_t frames, std::size_t max_groups, std::size_t min_frames);

// `current` with each group moved rigidly; `current` itself when the groups'
// map got blurrier (report.rejected) or there are fewer than three groups.
std::vector<Pose> refineGroups(const io::ScanSource& scans, const std::vector<Pose>& input,
                               const std::vector<Pose>& current, const RefineSettings& settings,
                               GroupRefinementReport& report, StageNotes& notes);

}  // namespace hba::refine
