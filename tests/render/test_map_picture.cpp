// Pictures: decoded back with stb_image, the map must be where it belongs.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <cmath>
#include <memory>
#include <random>
#include <regex>
#include <string>

#include "../eval/synthetic_scans.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/core/memory_budget.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/render/colormap.hpp"
#include "hba/render/map_picture.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "map_change.hpp"
#include "test_support.hpp"

namespace hba::render {
namespace {

// A wall at x = 5 (y in [-3, 3], z in [0, 2]) and a short trajectory.
MapPanel wallPanel(const std::string& title) {
  MapPanel panel;
  panel.title = title;
  for (double y = -3.0; y <= 3.0; y += 0.05) {
    for (double z = 0.0; z <= 2.0; z += 0.1)
      panel.map.add(Vec3f(5.0f, static_cast<float>(y), static_cast<float>(z)));
  }
  panel.trajectories.push_back(
      {"poses",
       {Pose(Quat::Identity(), Vec3(0, -2, 1)), Pose(Quat::Identity(), Vec3(0, 2, 1))},
       kOptimizedColor});
  return panel;
}

int brightness(Rgb c) { return c.r + c.g + c.b; }

TEST(MapPicture, WallIsDrawnWhereItStandsAndNothingElsewhere) {
  RenderSettings settings;
  settings.width = 900;
  settings.height = 600;
  settings.crop = Box2{-2, -5, 8, 5};
  const Picture picture = renderPanels({wallPanel("before"), wallPanel("after")}, settings);
  ASSERT_EQ(picture.image.width(), 900);
  ASSERT_EQ(picture.image.height(), 600);
  ASSERT_EQ(picture.top_views.size(), 2u);
  for (const TopViewTransform& view : picture.top_views) {
    const auto wall = view.toPixel(5.0, 1.0);
    const auto empty = view.toPixel(3.0, 1.0);  // open floor: no points
    const auto path = view.toPixel(0.0, 0.0);   // on the trajectory
    const Rgb on_wall = picture.image.at(static_cast<int>(wall.x()), static_cast<int>(wall.y()));
    const Rgb off_wall = picture.image.at(static_cast<int>(empty.x()), static_cast<int>(empty.y()));
    EXPECT_GT(brightness(on_wall), brightness(off_wall) + 100);
    EXPECT_LT(brightness(off_wall), 100);  // dark background
    EXPECT_GT(brightness(picture.image.at(static_cast<int>(path.x()), static_cast<int>(path.y()))), 600);
  }
  // Both panels share one view: the same world point, the same row.
  EXPECT_DOUBLE_EQ(picture.top_views[0].toPixel(5, 1).y(), picture.top_views[1].toPixel(5, 1).y());
}

TEST(MapPicture, PngRoundTripsThroughStbImage) {
  test::TempDir tmp;
  RenderSettings settings;
  settings.width = 640;
  settings.height = 400;
  settings.side_view = false;
  const Picture picture = renderPanels({wallPanel("map")}, settings);
  writePng(tmp / "map.png", picture.image);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(
      stbi_load((tmp / "map.png").c_str(), &w, &h, &channels, 3), stbi_image_free);
  ASSERT_TRUE(pixels);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 400);
  const auto wall = picture.top_views[0].toPixel(5.0, 0.5);
  const std::size_t i = (static_cast<std::size_t>(wall.y()) * 640 + static_cast<std::size_t>(wall.x())) * 3;
  const Rgb expected = picture.image.at(static_cast<int>(wall.x()), static_cast<int>(wall.y()));
  EXPECT_EQ(pixels.get()[i], expected.r);
  EXPECT_EQ(pixels.get()[i + 2], expected.b);
}

TEST(MapPicture, BadSettingsAreRejected) {
  EXPECT_THROW(parseBox("1,2,3"), Error);
  EXPECT_THROW(parseBox("0,0,-1,5"), Error);
  EXPECT_EQ(parseBox("-1.5,2,3,4.25").xmax, 3.0);
  RenderSettings tiny;
  tiny.width = 120;
  tiny.height = 120;
  EXPECT_THROW(renderPanels({wallPanel("a"), wallPanel("b")}, tiny), Error);
  EXPECT_THROW(renderPanels({}, RenderSettings{}), Error);
}

// The colours span the 2-98 % of heights, the side view's axis nearly all of
// them: its caption said "z -5.1..42.9 m" beside a bar of -1.0 to 27 m. Now it
// gives both ranges, and the colour range reads as the bar does.
TEST(MapPicture, SideCaptionAndColourBarAgree) {
  MapPanel panel = wallPanel("map");
  const std::size_t wall = panel.map.size();
  for (std::size_t i = 0; i < wall / 50; ++i) panel.map.add(Vec3f(5.0f, 0.0f, 40.0f));  // 2 %: a tree top
  RenderSettings settings;
  settings.width = 900;
  settings.height = 600;
  const Picture picture = renderPanels({panel}, settings);
  std::smatch colour, extent, low, high;
  const std::string number = "(-?[0-9]+(?:\\.[0-9])?)";
  ASSERT_TRUE(
      std::regex_search(picture.side_caption, extent, std::regex(", z " + number + "\\.\\." + number + " m")))
      << picture.side_caption;
  ASSERT_TRUE(std::regex_search(picture.side_caption, colour,
                                std::regex("colour " + number + "\\.\\." + number + " m \\(2-98 %\\)")))
      << picture.side_caption;
  ASSERT_TRUE(std::regex_match(picture.bar_low, low, std::regex("z " + number + " m"))) << picture.bar_low;
  ASSERT_TRUE(std::regex_match(picture.bar_high, high, std::regex(number + " m \\(2-98 %\\)")))
      << picture.bar_high;
  EXPECT_EQ(colour[1], low[1]);
  EXPECT_EQ(colour[2], high[1]);
  EXPECT_EQ(extent[2], "40");  // the axis reaches the tree top; the colours stop below it
  EXPECT_LT(std::stod(high[1]), 40.0);
}

TEST(Colormap, RunsFromDarkBlueToDarkRed) {
  EXPECT_GT(turbo(0.0).b, turbo(0.0).r);
  EXPECT_GT(turbo(1.0).r, turbo(1.0).b);
  EXPECT_GT(turbo(0.5).g, 200);
  EXPECT_EQ(brightness(turbo(-1.0)), brightness(turbo(0.0)));
}

TEST(RenderCli, BeforeAfterPictureOfASyntheticRun) {
  test::TempDir tmp;
  test::writeSyntheticDataset(tmp / "seq", test::syntheticPoses());
  Trajectory shifted;  // the "after" trajectory: the same, moved 0.3 m
  for (Pose p : test::syntheticPoses()) {
    p.t.y() += 0.3;
    shifted.poses.push_back(p);
  }
  io::writePoses(tmp / "after.txt", shifted, io::PoseFormat::Kitti);
  const auto run =
      test::runCommand(test::cliPath().string() + " render " + (tmp / "seq").string() + " --compare " +
                       (tmp / "after.txt").string() + " --gt " + (tmp / "seq" / "odom_poses.txt").string() +
                       " --width 1000 --height 700 -o " + (tmp / "cmp.png").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(
      stbi_load((tmp / "cmp.png").c_str(), &w, &h, &channels, 3), stbi_image_free);
  ASSERT_TRUE(pixels);
  EXPECT_EQ(w, 1000);
  EXPECT_EQ(h, 700);
  std::size_t lit = 0;  // pixels well above the dark background: map, lines, text
  for (int i = 0; i < w * h; ++i)
    lit += pixels.get()[3 * i] + pixels.get()[3 * i + 1] + pixels.get()[3 * i + 2] > 200;
  EXPECT_GT(lit, static_cast<std::size_t>(w * h / 20));

  const auto bad = test::runCommand(test::cliPath().string() + " render " + (tmp / "seq").string() +
                                    " --crop 1,2 -o " + (tmp / "x.png").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.png"));
}

// `hba render --compare` adds a zoom row under the requested height where
// planes got thinner: it logged the requested size, not the written one.
TEST(RenderCli, TheLogGivesTheSizeWritten) {
  test::TempDir tmp;
  const std::string hba = test::cliPath().string();
  const std::string sim = (tmp / "sim").string();
  ASSERT_EQ(test::runCommand(hba + " -q simulate --frames 30 --seed 3 -o " + sim).exit_code, 0);
  // The drifted odometry against the truth: planes get thinner, a zoom row.
  const auto run = test::runCommand(hba + " render " + sim + " --compare " + sim + "/gt.txt" +
                                    " --width 1000 --height 700 -o " + (tmp / "cmp.png").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int w = 0, h = 0, channels = 0;
  ASSERT_TRUE(stbi_info((tmp / "cmp.png").c_str(), &w, &h, &channels));
  EXPECT_EQ(w, 1000);
  EXPECT_GT(h, 700) << "no zoom row: the test proves nothing";
  EXPECT_NE(run.output.find("cmp.png (" + std::to_string(w) + "x" + std::to_string(h) + ")"),
            std::string::npos)
      << run.output;
}

// Pictures of scans held in memory are the PNGs `hba render` draws from the
// same scans in a folder, byte for byte: one map, and before/after.
TEST(RenderCli, SamePicturesFromScansInMemory) {
  test::TempDir tmp;
  test::writeSyntheticDataset(tmp / "seq", test::syntheticPoses());
  Trajectory shifted;
  for (Pose p : test::syntheticPoses()) {
    p.t.x() -= 0.2;
    shifted.poses.push_back(p);
  }
  io::writePoses(tmp / "after.txt", shifted, io::PoseFormat::Kitti);
  const std::string base =
      test::cliPath().string() + " render " + (tmp / "seq").string() + " --width 900 --height 600";
  ASSERT_EQ(test::runCommand(base + " -o " + (tmp / "map.png").string()).exit_code, 0);
  const auto compare =
      test::runCommand(base + " --compare " + (tmp / "after.txt").string() + " --gt " +
                       (tmp / "seq" / "odom_poses.txt").string() + " -o " + (tmp / "cmp.png").string());
  ASSERT_EQ(compare.exit_code, 0) << compare.output;

  // The poses as the tool reads them from the files.
  const std::vector<Pose> before = io::readPoses(tmp / "seq" / "odom_poses.txt").poses;
  const std::vector<Pose> after = io::readPoses(tmp / "after.txt").poses;
  const io::MemoryScanSource scans(test::syntheticScans(test::syntheticPoses()));
  RenderSettings settings;
  settings.width = 900;
  settings.height = 600;
  writeMapPicture(scans, before, nullptr, tmp / "memory_map.png", settings);
  writeBeforeAfter(scans, before, after, &before, tmp / "memory_cmp.png", settings);
  EXPECT_EQ(test::readText(tmp / "memory_map.png"), test::readText(tmp / "map.png"));
  EXPECT_EQ(test::readText(tmp / "memory_cmp.png"), test::readText(tmp / "cmp.png"));
}

// Rings of ground points as a spinning sensor sees them: as many a ring
// near the sensor as far out, so downsampling thins the near ones.
std::vector<PointCloud> ringScans(std::size_t count) {
  std::vector<PointCloud> scans(count);
  for (PointCloud& scan : scans) {
    for (double r = 2.0; r < 60.0; r *= 1.05) {
      for (int k = 0; k < 720; ++k) {
        const double a = k * M_PI / 360.0;
        scan.add(Vec3f(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), -1.5f));
      }
    }
  }
  return scans;
}

// Scans that come downsampled at the picture's voxel already (as `hba
// optimize` hands on the ones it kept) give the picture drawn from the
// scans as recorded, byte for byte.
TEST(RenderCli, ScansDownsampledBeforehandGiveTheSamePicture) {
  test::TempDir tmp;
  std::vector<Pose> before, after;
  for (int i = 0; i < 6; ++i) {
    before.emplace_back(Mat3(so3Exp(Vec3(0, 0, 0.2 * i))), Vec3(20.0 * i, 3.0 * i, 0.0));
    after.push_back(before.back());
    after.back().t.y() += 0.5;
  }
  const io::MemoryScanSource scans(ringScans(before.size()));
  RenderSettings settings;
  // Narrow: the overview's voxel is coarser than settings.voxel and follows
  // the sensor's reach, which must not depend on how the scans came.
  settings.width = 240;
  settings.height = 400;
  writeBeforeAfter(scans, before, after, nullptr, tmp / "raw.png", settings);
  const voxel::DownsampledScanSource downsampled(scans, settings.voxel);
  RenderSettings given = settings;
  given.scans_voxel = settings.voxel;
  writeBeforeAfter(downsampled, before, after, nullptr, tmp / "given.png", given);
  EXPECT_EQ(test::readText(tmp / "given.png"), test::readText(tmp / "raw.png"));
}

}  // namespace
}  // namespace hba::render

namespace hba::render {
namespace {

// A floor over [0, 20) m squared; where x >= 12 it is seen twice, 4 cm apart.
PointCloud floorMap(bool doubled) {
  PointCloud map;
  for (double x = 0.05; x < 20.0; x += 0.1) {
    for (double y = 0.05; y < 20.0; y += 0.1) {
      map.add(Vec3f(static_cast<float>(x), static_cast<float>(y), 0.0f));
      if (doubled && x >= 12.0) map.add(Vec3f(static_cast<float>(x), static_cast<float>(y), 0.04f));
    }
  }
  return map;
}

TEST(MapChange, DoubledPlanesAreThickAndTheZoomFindsWhereTheyGotThin) {
  const PointCloud before = floorMap(true), after = floorMap(false);
  const PlaneThickness doubled(before, 1.0), single(after, 1.0);
  const std::vector<float> thick = doubled.perPoint(before), thin = single.perPoint(after);
  EXPECT_NEAR(thick.back(), 0.02, 0.002);  // x near 20: doubled
  EXPECT_LT(thick.front(), 1e-4);          // x near 0: single
  EXPECT_LT(thin.back(), 1e-4);
  const std::optional<Box2> region = mostThinnedRegion(doubled, single, 6.0);
  ASSERT_TRUE(region);
  EXPECT_GE(region->xmin, 12.0);
  // The same map twice, or moved rigidly: no zoom.
  EXPECT_FALSE(mostThinnedRegion(single, single, 6.0));
}

// Scans of points scattered through a 40 m box: almost every point a voxel
// of its own, so that the maps grow by megabytes.
std::vector<PointCloud> scatteredScans(std::size_t count, std::size_t points) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f);
  std::vector<PointCloud> scans(count);
  for (PointCloud& scan : scans) {
    for (std::size_t i = 0; i < points; ++i)
      scan.add(Vec3f(coordinate(rng), coordinate(rng), coordinate(rng)));
  }
  return scans;
}

// A picture whose maps outgrow their budget stops before its file, with
// the error a caller can tell apart (hba optimize then leaves the picture
// out and keeps its results).
TEST(MapPicture, MapsThatOutgrowTheirBudgetStopBeforeTheFile) {
  test::TempDir tmp;
  std::vector<Pose> before, after;
  for (int i = 0; i < 20; ++i) {
    before.emplace_back(Quat::Identity(), Vec3(30.0 * i, 0.0, 0.0));
    after.push_back(before.back());
  }
  const io::MemoryScanSource scans(scatteredScans(before.size(), 20000));
  RenderSettings settings;
  settings.budget = MemoryBudget(std::size_t{1} << 20, "a test's");
  EXPECT_THROW(writeBeforeAfter(scans, before, after, nullptr, tmp / "before_after.png", settings),
               MemoryExceeded);
  EXPECT_THROW(writeMapPicture(scans, before, nullptr, tmp / "map.png", settings), MemoryExceeded);
  EXPECT_FALSE(std::filesystem::exists(tmp / "before_after.png"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "map.png"));
  // Without a limit both are drawn.
  settings.budget = MemoryBudget();
  writeMapPicture(scans, before, nullptr, tmp / "map.png", settings);
  EXPECT_TRUE(std::filesystem::exists(tmp / "map.png"));
}

}  // namespace
}  // namespace hba::render
