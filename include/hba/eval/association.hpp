#pragma once
// Pairing the poses of two trajectories before comparing them.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"

namespace hba::eval {

enum class AssociationMode {
  Auto,   // by time when both trajectories have stamps, by index otherwise
  Index,  // pose i with pose i; the counts must be equal
  Time    // each estimated pose with the nearest reference stamp within a tolerance
};

// Matched pose pairs, in increasing order of the estimate's index.
struct Association {
  std::vector<std::size_t> reference;             // index into the reference trajectory
  std::vector<std::size_t> estimate;              // index into the estimated trajectory
  AssociationMode mode = AssociationMode::Index;  // Index or Time: how the pairs were made
  std::size_t size() const { return reference.size(); }
};

// Pose i with pose i. Throws hba::Error if the counts differ: silently
// dropping a tail would hide a mismatched pair of files.
Association associateByIndex(std::size_t reference_count, std::size_t estimate_count);

// Each estimated stamp with the nearest reference stamp if |dt| <= max_diff;
// a reference pose is used at most once (the closer estimate wins). Stamps
// need not be sorted. Empty when nothing matches.
Association pairByTime(const std::vector<double>& reference_stamps,
                       const std::vector<double>& estimate_stamps, double max_diff);
// pairByTime, but throws hba::Error when nothing matches, with both sides'
// counts and time ranges.
Association associateByTime(const std::vector<double>& reference_stamps,
                            const std::vector<double>& estimate_stamps, double max_diff);

// "N stamps from A to B s" (the smallest and largest), for messages.
std::string describeStamps(const std::vector<double>& stamps);

// Whether `mode` pairs these two trajectories by time (Auto: both have stamps).
bool pairsByTime(const Trajectory& reference, const Trajectory& estimate, AssociationMode mode);

// Dispatches on `mode` (Auto as documented above). Throws hba::Error.
Association associate(const Trajectory& reference, const Trajectory& estimate, AssociationMode mode,
                      double max_time_diff);

}  // namespace hba::eval

namespace hba {
template <>
struct EnumNames<eval::AssociationMode> {
  static constexpr const char* what = "association";
  static constexpr EnumName<eval::AssociationMode> names[] = {{eval::AssociationMode::Auto, "auto"},
                                                              {eval::AssociationMode::Index, "index"},
                                                              {eval::AssociationMode::Time, "time"}};
};
}  // namespace hba
