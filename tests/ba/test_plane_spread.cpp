// The refinement spread over a group's processes (ba/plane_spread.hpp):
// members (threads standing in for mpirun's processes) that each hold
// whole chunks of the planes get the sums, the association and the poses
// of one process, bit for bit.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <thread>
#include <vector>

#include "factored_system.hpp"
#include "hba/ba/association.hpp"
#include "hba/ba/global_refinement.hpp"
#include "hba/ba/motion_prior.hpp"
#include "hba/ba/plane_spread.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "random_planes.hpp"
#include "same_poses.hpp"
#include "synthetic_window.hpp"
#include "threaded_group.hpp"

namespace hba::ba {
namespace {

// Runs body(member) for every member of `groups`, each on its own thread.
void eachMember(const test::ThreadedGroups& groups, const std::function<void(const dist::Group&)>& body) {
  std::vector<std::thread> threads;
  for (int rank = 0; rank < groups.size(); ++rank)
    threads.emplace_back([&, rank] { body(groups.member(rank)); });
  for (std::thread& thread : threads) thread.join();
}

std::vector<std::uint32_t> planeBegins(const std::vector<PlaneObservation>& planes) {
  std::vector<std::uint32_t> begin{0};
  for (const PlaneObservation& plane : planes)
    begin.push_back(begin.back() + static_cast<std::uint32_t>(plane.clusters.size()));
  return begin;
}

// 60 frames along a line, 6000 planes each seen by 12 consecutive frames:
// 72 000 observations, four chunks.
struct ManyPlanes {
  std::vector<Pose> poses;
  std::vector<PlaneObservation> planes;
  ManyPlanes() {
    std::mt19937 rng(11);
    const int frames = 60;
    const int reach = 12;
    for (int i = 0; i < frames; ++i)
      poses.emplace_back(so3Exp(0.1 * test::randomUnit(rng)), Vec3(i, 0.0, 0.0));
    for (int p = 0; p < 6000; ++p) {
      const auto first = static_cast<std::uint32_t>(p % (frames - reach + 1));
      std::vector<std::uint32_t> seen;
      for (std::uint32_t f = first; f < first + static_cast<std::uint32_t>(reach); ++f) seen.push_back(f);
      std::vector<Pose> near = poses;
      for (Pose& pose : near) pose.t -= poses[first].t;
      planes.push_back(test::randomPlane(rng, near, seen, 4, 0.01).observation);
    }
  }
};

TEST(PlaneSpread, MembersSummingTheirChunksGetTheSumsOfOneProcess) {
  const ManyPlanes many;
  const std::size_t frames = many.poses.size();
  const MotionPrior prior = neighbourPrior(many.poses, {}, MotionPriorSettings{});
  const PlaneProblem whole(many.planes, frames);
  const ObservationIndex whole_index(whole, frames);
  const FactoredSystem one(whole, prior, {}, whole_index, many.poses);
  const std::vector<std::uint32_t> begin = planeBegins(many.planes);
  const std::vector<std::size_t> chunks = sumChunks(begin, frames);
  ASSERT_GE(chunks.size(), 4u) << "the test needs several chunks";
  const Eigen::VectorXd x = Eigen::VectorXd::Random(static_cast<Eigen::Index>(6 * frames));
  const Eigen::VectorXd one_product = one.multiply(x);
  const double one_cost = whole.cost(many.poses);

  for (const int members : {2, 3}) {
    test::ThreadedGroups groups(members);
    std::vector<std::size_t> held(static_cast<std::size_t>(members));
    eachMember(groups, [&](const dist::Group& group) {
      PlaneSpread spread;
      spread.group = &group;
      spread.chunk_begin = chunks;
      // Shares of about equal plane counts, moved to whole chunks.
      std::vector<std::size_t> plane_start;
      for (int m = 0; m <= members; ++m)
        plane_start.push_back(many.planes.size() * static_cast<std::size_t>(m) /
                              static_cast<std::size_t>(members));
      const std::vector<std::size_t> starts = memberChunkStarts(chunks, plane_start);
      spread.first_chunk = starts[static_cast<std::size_t>(group.rank())];
      spread.end_chunk = starts[static_cast<std::size_t>(group.rank()) + 1];
      const std::vector<PlaneObservation> mine(
          many.planes.begin() + static_cast<long>(spread.firstPlane()),
          many.planes.begin() + static_cast<long>(chunks[spread.end_chunk]));
      held[static_cast<std::size_t>(group.rank())] = mine.size();
      const PlaneProblem part(mine, frames, spread);
      const ObservationIndex index(part, frames);
      const FactoredSystem system(part, prior, {}, index, many.poses);
      EXPECT_EQ(system.cost(), one.cost()) << members << " members";
      EXPECT_TRUE(system.gradient() == one.gradient()) << members << " members";
      for (std::size_t i = 0; i < frames; ++i) EXPECT_TRUE(system.block(i) == one.block(i)) << "frame " << i;
      EXPECT_TRUE(system.multiply(x) == one_product) << members << " members";
      EXPECT_EQ(part.cost(many.poses), one_cost);
      EXPECT_THROW(system.upperTriangle(), Error);  // the dense solve is one process's
    });
    for (const std::size_t n : held) EXPECT_GT(n, 0u) << members << " members: one holds no plane";
  }
}

// A 40-frame drive past nine 16 m walls, in 1 m voxels: some 90 000
// observations, five chunks.
test::SyntheticWindow drive() {
  test::SyntheticWindowSpec spec;
  spec.frames = 40;
  spec.grid = 20.0;
  spec.patch_size = 16.0;
  spec.points_per_patch = 1200;
  spec.noise_sigma = 0.01;
  spec.perturb_angle_deg = 0.2;
  spec.perturb_translation = 0.03;
  spec.seed = 5;
  return test::makeSyntheticWindow(spec);
}

RefinementSettings fineVoxels() {
  RefinementSettings settings;
  settings.planes.voxel_size = 1.0;
  return settings;
}

TEST(PlaneSpread, MembersAssociateAndRefineAsOneProcess) {
  const test::SyntheticWindow window = drive();
  const std::vector<const PointCloud*> scans = window.scanPointers();
  const RefinementSettings settings = fineVoxels();
  const Association one = refinementAssociation(scans, window.initial, settings);
  const std::vector<std::uint32_t> begin = planeBegins(one.problem.planes());
  ASSERT_GE(sumChunks(begin, window.initial.size()).size(), 4u)
      << "the test needs several chunks: " << begin.back() << " observations";
  const RefinementResult one_result = refineGlobally(scans, window.initial, settings);
  ASSERT_GT(one_result.iterations, 0);

  for (const int members : {2, 3}) {
    test::ThreadedGroups groups(members);
    std::vector<std::vector<PlaneObservation>> held(static_cast<std::size_t>(members));
    std::vector<RefinementResult> results(static_cast<std::size_t>(members));
    eachMember(groups, [&](const dist::Group& group) {
      RefinementSettings spread = settings;
      spread.spread_over = &group;
      const Association mine = refinementAssociation(scans, window.initial, spread);
      EXPECT_TRUE(mine.problem.spread().spread());
      EXPECT_EQ(mine.plane_costs, one.plane_costs);
      EXPECT_EQ(mine.cost(), one.cost());
      held[static_cast<std::size_t>(group.rank())] = mine.problem.planes();
      results[static_cast<std::size_t>(group.rank())] = refineGlobally(scans, window.initial, spread);
    });
    // The members' planes, one after another, are one process's.
    std::vector<PlaneObservation> joined;
    for (const auto& planes : held) joined.insert(joined.end(), planes.begin(), planes.end());
    ASSERT_EQ(joined.size(), one.problem.numPlanes()) << members << " members";
    for (std::size_t p = 0; p < joined.size(); ++p) {
      const auto& a = joined[p].clusters;
      const auto& b = one.problem.planes()[p].clusters;
      ASSERT_EQ(a.size(), b.size()) << "plane " << p;
      for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].frame, b[k].frame);
        EXPECT_EQ(a[k].count(), b[k].count());
        EXPECT_TRUE(a[k].mean() == b[k].mean());
        EXPECT_TRUE(a[k].scatter() == b[k].scatter());
      }
    }
    for (const RefinementResult& result : results) {
      test::expectSamePoses(result.poses, one_result.poses);
      EXPECT_EQ(result.iterations, one_result.iterations);
      EXPECT_EQ(result.cg_products, one_result.cg_products);
      EXPECT_EQ(result.planes, one_result.planes);
      EXPECT_EQ(result.observations, one_result.observations);
      EXPECT_EQ(result.plane_points, one_result.plane_points);
      EXPECT_EQ(result.cost_after, one_result.cost_after);
    }
  }
}

}  // namespace
}  // namespace hba::ba
