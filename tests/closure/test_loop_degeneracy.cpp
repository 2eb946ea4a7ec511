// Places whose planes leave directions free: the check must say so rather
// than hand the pose graph a factor that claims to know them.
#include <gtest/gtest.h>

#include <vector>

#include "hba/closure/loop_check.hpp"
#include "simulated_scans.hpp"

namespace hba::closure {
namespace {

// Out along x and back: frame k and frame 39 - k stand at the same place.
std::vector<Pose> outAndBack() {
  std::vector<Pose> poses;
  for (std::size_t k = 0; k < 40; ++k) {
    const double x = 0.5 * static_cast<double>(k < 20 ? k : 39 - k);
    poses.emplace_back(Quat::Identity(), Vec3(x, 0.0, 1.8));
  }
  return poses;
}

std::vector<Vec3> flatField() {
  std::vector<Vec3> points;
  for (double x = -40.0; x <= 50.0; x += 0.25) {
    for (double y = -40.0; y <= 40.0; y += 0.25) points.emplace_back(x, y, 0.0);
  }
  return points;
}

// A floor 6 m wide between two 3 m walls, running along x.
std::vector<Vec3> corridor() {
  std::vector<Vec3> points;
  for (double x = -40.0; x <= 50.0; x += 0.2) {
    for (double y = -3.0; y <= 3.0; y += 0.2) points.emplace_back(x, y, 0.0);
    for (double z = 0.0; z <= 3.0; z += 0.2) {
      points.emplace_back(x, -3.0, z);
      points.emplace_back(x, 3.0, z);
    }
  }
  return points;
}

LoopCheck checkPlace(const std::vector<Vec3>& world, double search_radius_m = 0.0) {
  const std::vector<Pose> poses = outAndBack();
  const io::MemoryScanSource scans(test::handMadeScans(poses, world, 30.0));
  LoopCheckSettings settings;
  settings.neighbourhood_frames = 3;
  settings.search_radius_m = search_radius_m;
  return verifyLoop(scans, poses, {5, 34, std::nullopt}, settings);
}

TEST(LoopDegeneracy, FlatFieldIsRejectedForItsFreeDirections) {
  const LoopCheck result = checkPlace(flatField());
  EXPECT_FALSE(result.accepted);
  EXPECT_NE(result.reason.find("free"), std::string::npos) << result.reason;
  // The search finds no structure to match at all.
  const LoopCheck searched = checkPlace(flatField(), 4.0);
  EXPECT_FALSE(searched.accepted);
  EXPECT_NE(searched.reason.find("0 structure cells"), std::string::npos) << searched.reason;
}

TEST(LoopDegeneracy, CorridorIsRejectedForSlidingAlongIt) {
  const LoopCheck result = checkPlace(corridor());
  EXPECT_FALSE(result.accepted);
  EXPECT_NE(result.reason.find("translation along (1.00, 0.00, 0.00)"), std::string::npos) << result.reason;
  // Shifted along it, the walls look the same: the search says so.
  const LoopCheck searched = checkPlace(corridor(), 4.0);
  EXPECT_FALSE(searched.accepted);
  EXPECT_NE(searched.reason.find("ambiguous"), std::string::npos) << searched.reason;
}

}  // namespace
}  // namespace hba::closure
