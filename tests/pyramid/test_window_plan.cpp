#include <gtest/gtest.h>

#include <string>

#include "hba/core/error.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pyramid {
namespace {

void expectCoversAllWithOverlap(std::size_t frames, int w, int s) {
  const auto windows = planWindows(frames, w, s);
  ASSERT_FALSE(windows.empty());
  EXPECT_EQ(windows.front().first, 0u);
  EXPECT_EQ(windows.back().first + windows.back().count, frames);
  for (std::size_t j = 0; j < windows.size(); ++j) {
    EXPECT_LE(windows[j].count, static_cast<std::size_t>(w));
    EXPECT_GE(windows[j].count, std::min<std::size_t>(frames, 2));
    if (j > 0) {
      // Window j starts at j*s and overlaps its predecessor.
      EXPECT_EQ(windows[j].first, j * static_cast<std::size_t>(s));
      EXPECT_LT(windows[j].first, windows[j - 1].first + windows[j - 1].count);
    }
  }
}

TEST(WindowPlan, ExactFit) {
  const auto windows = planWindows(20, 10, 5);
  ASSERT_EQ(windows.size(), 3u);
  EXPECT_EQ(windows[2].first, 10u);
  EXPECT_EQ(windows[2].count, 10u);
}

TEST(WindowPlan, TailIsShorterButCovered) {
  const auto windows = planWindows(23, 10, 5);
  ASSERT_EQ(windows.size(), 4u);
  EXPECT_EQ(windows[3].first, 15u);
  EXPECT_EQ(windows[3].count, 8u);
  const auto eleven = planWindows(11, 10, 5);
  ASSERT_EQ(eleven.size(), 2u);
  EXPECT_EQ(eleven[1].first, 5u);
  EXPECT_EQ(eleven[1].count, 6u);
}

TEST(WindowPlan, ShortLayerIsOneWindow) {
  const auto windows = planWindows(7, 10, 5);
  ASSERT_EQ(windows.size(), 1u);
  EXPECT_EQ(windows[0].count, 7u);
  EXPECT_TRUE(planWindows(0, 10, 5).empty());
}

TEST(WindowPlan, ManyShapesCoverEveryFrame) {
  for (std::size_t n : {2u, 9u, 10u, 11u, 12u, 57u, 1000u, 1003u}) {
    for (auto [w, s] : {std::pair{10, 5}, std::pair{6, 3}, std::pair{4, 1}, std::pair{2, 1}}) {
      SCOPED_TRACE(testing::Message() << "n=" << n << " w=" << w << " s=" << s);
      expectCoversAllWithOverlap(n, w, s);
    }
  }
}

TEST(WindowPlan, RejectsWindowsThatDoNotOverlap) {
  EXPECT_THROW(planWindows(100, 10, 10), Error);
  EXPECT_THROW(planWindows(100, 10, 0), Error);
  EXPECT_THROW(planWindows(100, 1, 1), Error);
}

TEST(WindowPlan, OwnFramesRunToTheNextWindow) {
  const std::vector<Window> uneven{{0, 6}, {3, 6}, {7, 7}};
  EXPECT_EQ(ownFrames(uneven, 0).first, 0u);
  EXPECT_EQ(ownFrames(uneven, 0).count, 3u);
  EXPECT_EQ(ownFrames(uneven, 1).first, 3u);
  EXPECT_EQ(ownFrames(uneven, 1).count, 4u);
  EXPECT_EQ(ownFrames(uneven, 2).first, 7u);  // the last window: all its frames
  EXPECT_EQ(ownFrames(uneven, 2).count, 7u);
  EXPECT_EQ(planFrames(uneven), 14u);
  // Every frame is owned by exactly one window.
  const auto plan = planWindows(1003, 10, 5);
  std::size_t next = 0;
  for (std::size_t j = 0; j < plan.size(); ++j) {
    EXPECT_EQ(ownFrames(plan, j).first, next);
    next += ownFrames(plan, j).count;
  }
  EXPECT_EQ(next, 1003u);
}

TEST(WindowPlan, CheckAcceptsPlannedAndUnevenPlans) {
  for (std::size_t n : {1u, 2u, 10u, 11u, 57u, 1003u}) {
    EXPECT_NO_THROW(checkWindowPlan(planWindows(n, 10, 5), n)) << n;
  }
  EXPECT_NO_THROW(checkWindowPlan({{0, 6}, {3, 6}, {7, 7}}, 14));
}

TEST(WindowPlan, CheckRejectsPlansThatCannotChain) {
  auto message = [](const std::vector<Window>& plan, std::size_t frames) {
    try {
      checkWindowPlan(plan, frames);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({}, 3).find("no windows"), std::string::npos);
  EXPECT_NE(message({{1, 5}}, 6).find("does not start at frame 0"), std::string::npos);
  // A gap: window 1 starts after window 0's last frame.
  EXPECT_NE(message({{0, 4}, {4, 4}}, 8).find("window 1 (frames 4-7) does not start inside window 0"),
            std::string::npos);
  EXPECT_NE(message({{0, 4}, {0, 4}}, 4).find("does not start inside"), std::string::npos);
  EXPECT_NE(message({{0, 4}, {2, 0}}, 4).find("window 1 is empty"), std::string::npos);
  EXPECT_NE(message({{0, 4}, {2, 4}}, 9).find("end at frame 6"), std::string::npos);
}

TEST(LayerCount, PaperFormula) {
  // DESIGN.md: the formula gives 4 for N = 1101, w = 10, s = 5, n = 8.
  EXPECT_EQ(paperLayerCount(1101, 10, 5, 8), 4);
  // Larger sequences never get fewer layers.
  int previous = 1;
  for (std::size_t n : {50u, 300u, 1000u, 5000u, 20000u, 100000u}) {
    const int layers = paperLayerCount(n, 10, 5, 2);
    EXPECT_GE(layers, previous);
    EXPECT_LE(layers, maxLayerCount(n, 10, 5));
    previous = layers;
  }
}

TEST(LayerCount, MaxLayersStopsWhenTopFitsOneWindow) {
  EXPECT_EQ(maxLayerCount(10, 10, 5), 1);
  EXPECT_EQ(maxLayerCount(11, 10, 5), 2);   // 11 frames -> 2 windows -> 2 keyframes
  EXPECT_EQ(maxLayerCount(300, 10, 5), 4);  // 300 -> 59 -> 11 -> 2
}

}  // namespace
}  // namespace hba::pyramid
