// The closure stage spread over the members of a group (threads standing in
// for mpirun's processes): each member verifies its share of the
// candidates, and the outcome is that of one process, bit for bit.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "hba/io/scan_source.hpp"
#include "hba/sim/simulation.hpp"
#include "hba/voxel/downsample.hpp"
#include "pipeline/closure_stage.hpp"
#include "simulated_sequence.hpp"
#include "threaded_group.hpp"

namespace hba::pipeline {
namespace {

// A short drive (solid-state sensor) and loop pairs along it: some close
// enough that both ends see the same walls, some not.
struct Case {
  io::MemoryScanSource clouds;
  std::vector<Pose> initial;
  ClosureInputs closures;
};

const Case& drive() {
  static const Case c = [] {
    const test::Sequence sequence = test::simulateSequence(test::smallDriveConfig(40));
    std::vector<PointCloud> clouds;
    for (const PointCloud& scan : sequence.scans) clouds.push_back(voxel::downsample(scan, 0.1));
    ClosureInputs closures;
    for (const auto& [from, to] : std::vector<std::pair<std::size_t, std::size_t>>{
             {0, 11}, {5, 17}, {10, 22}, {15, 27}, {20, 32}, {25, 37}, {0, 30}, {3, 38}}) {
      closures.loops.push_back({from, to, std::nullopt});
    }
    return Case{io::MemoryScanSource(std::move(clouds)), sequence.initial, closures};
  }();
  return c;
}

void expectSameReport(const ClosureReport& a, const ClosureReport& b, int members) {
  ASSERT_EQ(a.loops.size(), b.loops.size());
  EXPECT_EQ(a.verified, b.verified) << members << " members";
  EXPECT_EQ(a.loops_used, b.loops_used) << members << " members";
  for (std::size_t k = 0; k < a.loops.size(); ++k) {
    const LoopReport& x = a.loops[k];
    const LoopReport& y = b.loops[k];
    EXPECT_EQ(x.from, y.from);
    EXPECT_EQ(x.verified, y.verified) << members << " members, candidate " << k;
    EXPECT_EQ(x.used, y.used) << members << " members, candidate " << k;
    EXPECT_EQ(x.reason, y.reason) << members << " members, candidate " << k;
    EXPECT_EQ(x.shared_planes, y.shared_planes) << members << " members, candidate " << k;
    EXPECT_EQ(x.overlap, y.overlap) << members << " members, candidate " << k;
    EXPECT_EQ(x.rms_m, y.rms_m) << members << " members, candidate " << k;
    EXPECT_EQ(x.correction_m, y.correction_m) << members << " members, candidate " << k;
    EXPECT_EQ(x.correction_deg, y.correction_deg) << members << " members, candidate " << k;
  }
}

TEST(ClosureStage, MembersOfAGroupVerifyTheirShareAndGetTheOutcomeOfOneProcess) {
  const Case& c = drive();
  const HbaSettings settings;
  const ClosureOutcome alone = runClosureStage(c.clouds, c.initial, c.closures, settings);
  ASSERT_EQ(alone.report.loops.size(), c.closures.loops.size());
  // Both kinds of outcome are compared: some pairs verified and closed, some not.
  EXPECT_GT(alone.report.verified, 0u);
  EXPECT_LT(alone.report.verified, c.closures.loops.size());
  EXPECT_GT(alone.loops.size(), 0u);
  for (const int size : {2, 3}) {
    hba::test::ThreadedGroups groups(size);
    std::vector<ClosureOutcome> outcomes(static_cast<std::size_t>(size));
    std::vector<std::thread> members;
    for (int rank = 0; rank < size; ++rank) {
      members.emplace_back([&, rank] {
        outcomes[static_cast<std::size_t>(rank)] =
            runClosureStage(c.clouds, c.initial, c.closures, settings, groups.member(rank));
      });
    }
    for (std::thread& member : members) member.join();
    const ClosureOutcome& first = outcomes.front();
    expectSameReport(alone.report, first.report, size);
    ASSERT_EQ(first.start.size(), alone.start.size());
    for (std::size_t i = 0; i < alone.start.size(); ++i) {
      ASSERT_EQ(first.start[i].t, alone.start[i].t) << size << " members, frame " << i;
      ASSERT_EQ(first.start[i].q.coeffs(), alone.start[i].q.coeffs()) << size << " members, frame " << i;
    }
    ASSERT_EQ(first.loops.size(), alone.loops.size());
    for (std::size_t k = 0; k < alone.loops.size(); ++k) {
      EXPECT_EQ(first.loops[k].from, alone.loops[k].from);
      EXPECT_EQ(first.loops[k].to, alone.loops[k].to);
      EXPECT_EQ(first.loops[k].measurement.t, alone.loops[k].measurement.t) << size << " members, loop " << k;
      EXPECT_EQ(first.loops[k].information, alone.loops[k].information) << size << " members, loop " << k;
    }
  }
}

}  // namespace
}  // namespace hba::pipeline
