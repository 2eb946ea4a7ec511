#include "harness.hpp"

namespace hba::fuzz {

const std::vector<Target>& allTargets() {
  // clang-format 14 and 19 indent this table differently (the #if inside):
  // kept as written.
  // clang-format off
  static const std::vector<Target> targets = {
    {"fuzz_pcd", feedPcd},
    {"fuzz_ply", feedPly},
    {"fuzz_kitti_bin", feedKittiBin},
    {"fuzz_las", feedLas},
    {"fuzz_pose_hba", feedHbaPoses},
    {"fuzz_pose_kitti", feedKittiPoses},
    {"fuzz_pose_tum", feedTumPoses},
    {"fuzz_settings_yaml", feedSettingsYaml},
    {"fuzz_loop_file", feedLoopFile},
    {"fuzz_prior_file", feedPriorFile},
    {"fuzz_report_json", feedReportJson},
#if HBA_FUZZ_RECORDINGS  // hba built with recordings (HBA_WITH_RECORDINGS)
    {"fuzz_ros1_bag", feedRos1Bag},
    {"fuzz_db3", feedDb3},
    {"fuzz_rosbag2_metadata", feedRosbag2Metadata},
    {"fuzz_ros_message", feedRosMessage},
    {"fuzz_mcap", feedMcap},
#endif
  };
  // clang-format on
  return targets;
}

}  // namespace hba::fuzz
