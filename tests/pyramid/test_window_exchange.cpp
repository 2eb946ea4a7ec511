// A layer's windows spread over the members of a group: who runs which,
// and what they send each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "dist/bytes.hpp"
#include "hba/core/error.hpp"
#include "pipeline/shared_outcomes.hpp"
#include "window_exchange.hpp"

namespace hba::pyramid {
namespace {

// Every window once, in order, member by member; no member's work above
// an even share by more than one window's.
void expectFairSplit(const std::vector<double>& work, int size) {
  const double total = std::accumulate(work.begin(), work.end(), 0.0);
  const double largest = work.empty() ? 0.0 : *std::max_element(work.begin(), work.end());
  std::size_t next = 0;
  for (int rank = 0; rank < size; ++rank) {
    const WindowRange range = windowsOfMember(work, rank, size);
    ASSERT_EQ(range.first, next) << "member " << rank << " of " << size;
    ASSERT_LE(range.first, range.end);
    double mine = 0.0;
    for (std::size_t w = range.first; w < range.end; ++w) mine += work[w];
    EXPECT_LE(mine, total / size + largest + 1e-9) << "member " << rank << " of " << size;
    next = range.end;
  }
  EXPECT_EQ(next, work.size());
}

TEST(WindowExchange, MembersSplitTheWorkInConsecutiveRanges) {
  expectFairSplit(std::vector<double>(199, 10.0), 1);
  expectFairSplit(std::vector<double>(199, 10.0), 2);
  expectFairSplit(std::vector<double>(199, 10.0), 4);
  // Keyframes of very different sizes: split by points, not by count.
  std::vector<double> uneven;
  for (int k = 0; k < 40; ++k) uneven.push_back(k < 10 ? 1000.0 : 10.0);
  expectFairSplit(uneven, 3);
  const WindowRange first = windowsOfMember(uneven, 0, 2);
  EXPECT_LT(first.end, 10u);  // half the points lie in the first few windows
  // Fewer windows than members: some get none; no work: split by count.
  expectFairSplit({5.0}, 4);
  expectFairSplit(std::vector<double>(7, 0.0), 3);
  expectFairSplit({}, 2);
  EXPECT_EQ(windowsOfMember(std::vector<double>(6, 1.0), 0, 1).end, 6u);
  EXPECT_THROW(windowsOfMember({1.0}, 2, 2), Error);
  EXPECT_THROW(windowsOfMember({1.0}, 0, 0), Error);
}

// The next layer's windows of a member read the frames they cover: the
// keyframes sent to it, and only those.
TEST(WindowExchange, AMembersWindowsReadTheFramesTheyCover) {
  const std::vector<Window> plan{{0, 10}, {5, 10}, {10, 10}, {15, 7}};
  EXPECT_EQ(framesOf(plan, {0, 1}).first, 0u);
  EXPECT_EQ(framesOf(plan, {0, 1}).end, 10u);
  EXPECT_EQ(framesOf(plan, {1, 4}).first, 5u);
  EXPECT_EQ(framesOf(plan, {1, 4}).end, 22u);
  EXPECT_EQ(framesOf(plan, {2, 2}).end, 0u);  // no window, no frame
  std::vector<std::size_t> points(22, 1);
  points[0] = 100;
  const auto frame_work = [&](std::size_t i) { return static_cast<double>(points.at(i)); };
  EXPECT_EQ(workOf(plan, frame_work), (std::vector<double>{109, 10, 10, 7}));
  EXPECT_THROW(workOf({{20, 5}}, frame_work), std::out_of_range);
}

TEST(WindowExchange, BytesComeBackAndAShortMessageIsRefused) {
  dist::ByteWriter out;
  out.put(3.25);
  out.put(Vec3(1, -2, 1e6));
  out.putVector(std::vector<Vec3f>{Vec3f(1, 2, 3), Vec3f(-4, 5.5f, 6)});
  out.putVector(std::vector<float>{});
  const dist::Bytes bytes = out.take();
  dist::ByteReader in(bytes);
  EXPECT_EQ(in.get<double>(), 3.25);
  EXPECT_EQ(in.get<Vec3>(), Vec3(1, -2, 1e6));
  const std::vector<Vec3f> points = in.getVector<Vec3f>();
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1], Vec3f(-4, 5.5f, 6));
  EXPECT_TRUE(in.getVector<float>().empty());
  EXPECT_TRUE(in.done());
  EXPECT_THROW(in.get<std::uint8_t>(), Error);

  const dist::Bytes cut(bytes.begin(), bytes.begin() + 20);
  dist::ByteReader short_in(cut);
  short_in.get<double>();
  try {
    short_in.get<Vec3>();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ends early"), std::string::npos) << e.what();
  }
}

TEST(WindowExchange, WindowShapeFactorsComeBackWhole) {
  graph::WindowShapeFactor shape;
  shape.nodes = {4, 9, 14};
  shape.relative = {Pose(Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())), Vec3(1, 2, 3)),
                    Pose(Quat::Identity(), Vec3(-1, 0.5, 7))};
  shape.information = Eigen::MatrixXd::Random(12, 12);
  dist::ByteWriter out;
  putShapes(out, {shape, shape});
  const dist::Bytes bytes = out.take();
  dist::ByteReader in(bytes);
  const std::vector<graph::WindowShapeFactor> back = getShapes(in);
  EXPECT_TRUE(in.done());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].nodes, shape.nodes);
  ASSERT_EQ(back[1].relative.size(), 2u);
  EXPECT_EQ(back[1].relative[0].t, shape.relative[0].t);
  EXPECT_EQ(back[1].relative[0].q.coeffs(), shape.relative[0].q.coeffs());
  EXPECT_EQ(back[1].information, shape.information);  // column order kept
}

}  // namespace
}  // namespace hba::pyramid
