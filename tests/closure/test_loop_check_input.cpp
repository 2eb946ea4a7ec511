// Invalid input is an hba::Error that names the problem.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include "hba/closure/loop_check.hpp"
#include "hba/core/error.hpp"

namespace hba::closure {
namespace {

// Runs `call`, which must throw hba::Error whose message contains `fragment`.
void expectError(const std::function<void()>& call, const std::string& fragment) {
  try {
    call();
    ADD_FAILURE() << "no hba::Error (expected one mentioning '" << fragment << "')";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

io::MemoryScanSource threeScans() {
  PointCloud cloud;
  cloud.add(Vec3f(1, 2, 3));
  return io::MemoryScanSource({cloud, cloud, cloud});
}

TEST(LoopCheckInput, RefusesBadPairsAndPoses) {
  const io::MemoryScanSource scans = threeScans();
  const std::vector<Pose> poses(3);
  expectError([&] { verifyLoop(scans, poses, {0, 3, std::nullopt}, {}); }, "out of range");
  expectError([&] { verifyLoop(scans, poses, {1, 1, std::nullopt}, {}); }, "same frame");
  const std::vector<Pose> two_poses(2);
  expectError([&] { verifyLoop(scans, two_poses, {0, 2, std::nullopt}, {}); }, "2 poses for 3 scans");
}

TEST(LoopCheckInput, RefusesInvalidSettings) {
  LoopCheckSettings settings;
  settings.final_voxel_size = 8.0;
  expectError([&] { validate(settings); }, "final_voxel_size");
  settings = {};
  settings.max_sigma_ratio = 0.5;
  expectError([&] { validate(settings); }, "max_sigma_ratio");
  settings = {};
  settings.search_radius_m = -1.0;
  expectError([&] { validate(settings); }, "search_radius_m");
}

TEST(LoopCheckInput, NeighbourhoodsThatShareFramesAreNoLoop) {
  const io::MemoryScanSource scans = threeScans();
  const LoopCheck result = verifyLoop(scans, std::vector<Pose>(3), {0, 2, std::nullopt}, {});
  EXPECT_FALSE(result.accepted);
  EXPECT_NE(result.reason.find("share frames"), std::string::npos) << result.reason;
}

}  // namespace
}  // namespace hba::closure
