#pragma once
// The last stage of hba optimize: the self-check on the input's planes and
// the sparse plane BA over every layer-1 frame, in blocks, then rigid
// groups (docs/pyramid.md, "Refinement and self-check").
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "hba/ba/global_refinement.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/factors.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/refine/report.hpp"

namespace hba::refine {

// Two maps this close measure alike: equal maps differ by rounding and
// plane edges. Every "less consistent than" test allows it.
inline constexpr double kEqualMapMargin = 1.005;

// What the stage reads of the run's settings (HbaSettings::refineSettings(),
// whose table holds the defaults).
struct RefineSettings {
  ba::RefinementSettings ba;  // the blocks' and groups' plane BA
  bool refine{};              // off: the self-check alone
  bool groups{};              // rigid groups after the blocks
  double scan_voxel{};        // m; 0 = the scans as given
  std::size_t max_points{};   // a block's points at most
  std::size_t group_min_frames{};
  std::size_t group_max_count{};
  double group_voxel{};  // m
};

// What the stage is told of the hierarchy before it.
struct HierarchyFacts {
  int layers = 0;  // 1: the hierarchy was one global BA, nothing to refine
  // Points layer 1 held: more than max_points means several blocks follow.
  std::size_t layer_one_points = 0;
  // The scans source keeps what it reads (TimedClouds with keep): the blocks
  // and groups need no copy of their own.
  bool scans_kept = false;
};

// Warnings and time the stage adds to the run's report.
struct StageNotes {
  std::vector<std::string> warnings;
  double seconds_voxelize = 0.0;
  double seconds_solve = 0.0;
  void warn(std::string message);  // logged too
  void add(const StageNotes& other);
};

struct RefineOutcome {
  std::vector<Pose> poses;
  ConsistencyReport consistency;
  RefinementReport refinement;
  StageNotes notes;
};

// The first block read and its input's planes found before the
// hierarchy's poses are known: none of it needs them while the hierarchy
// keeps the first frame where the input has it (it holds it unless
// position priors place the map). The pipeline makes it beside the last
// pose graph, which runs on one thread. Taken whole by refineAndCheck.
class PreparedStart {
 public:
  struct Parts;
  PreparedStart();
  PreparedStart(PreparedStart&&) noexcept;
  PreparedStart& operator=(PreparedStart&&) noexcept;
  ~PreparedStart();
  std::unique_ptr<Parts> parts;
};
PreparedStart prepareStart(const io::ScanSource& scans, const std::vector<Pose>& initial,
                           const HierarchyFacts& facts, const RefineSettings& settings);

// The final poses from the input poses and the hierarchy's. `priors` (the
// closure stage's kept ones, in the poses' coordinates) hold the
// refinement's long-range shape. `prepared`: prepareStart's of the same
// scans, input and settings (its planes are found again where the
// hierarchy moved the first frame).
RefineOutcome refineAndCheck(const io::ScanSource& scans, const std::vector<Pose>& initial,
                             const std::vector<Pose>& hierarchy, const HierarchyFacts& facts,
                             const std::vector<graph::PositionPriorFactor>& priors,
                             const RefineSettings& settings, PreparedStart* prepared = nullptr);

}  // namespace hba::refine
