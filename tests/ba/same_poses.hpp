#pragma once
// Two sets of poses equal to the bit: what spreading or reusing work must
// leave alone.
#include <gtest/gtest.h>

#include <vector>

#include "hba/core/pose.hpp"

namespace hba::test {

inline void expectSamePoses(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].t == b[i].t) << "frame " << i;
    EXPECT_TRUE(a[i].q.coeffs() == b[i].q.coeffs()) << "frame " << i;
  }
}

}  // namespace hba::test
