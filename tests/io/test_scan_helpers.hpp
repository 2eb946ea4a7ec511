#pragma once
// Comparisons and error checks shared by the scan I/O tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "hba/core/error.hpp"
#include "hba/core/point_cloud.hpp"
#include "test_support.hpp"

namespace hba::test {

inline std::filesystem::path pcdFixture(const std::string& name) { return dataDir() / "pcd" / name; }
inline std::filesystem::path plyFixture(const std::string& name) { return dataDir() / "ply" / name; }
inline std::filesystem::path binFixture(const std::string& name) { return dataDir() / "bin" / name; }

// Bit-exact equality of points and intensities.
inline void expectSameCloud(const PointCloud& expected, const PointCloud& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  ASSERT_EQ(expected.hasIntensity(), actual.hasIntensity());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(expected.points[i], actual.points[i]) << "point " << i;
    if (expected.hasIntensity()) {
      ASSERT_EQ(expected.intensity[i], actual.intensity[i]) << "point " << i;
    }
  }
}

// Equality up to `tolerance` per coordinate (for text written with fewer digits).
inline void expectNearCloud(const PointCloud& expected, const PointCloud& actual, float tolerance) {
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_LE((expected.points[i] - actual.points[i]).cwiseAbs().maxCoeff(), tolerance) << "point " << i;
  }
}

// Runs `action`, which must throw hba::Error; returns the message.
inline std::string errorMessage(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected an hba::Error";
  return {};
}

// The error names the file and says what is wrong (contains `problem`).
inline void expectErrorAbout(const std::filesystem::path& path, const std::string& problem,
                             const std::function<void()>& action) {
  const std::string message = errorMessage(action);
  EXPECT_NE(message.find(path.string() + ": "), std::string::npos) << message;
  EXPECT_NE(message.find(problem), std::string::npos) << "expected '" << problem << "' in: " << message;
}

inline PointCloud makeCloud(std::size_t n, bool with_intensity) {
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const float t = static_cast<float>(i);
    // Values with full float mantissas, to catch any lossy text conversion.
    const Vec3f p(0.1f * t + 1.0f / 3.0f, -0.7f * t + 1e-7f * t * t, 123.456789f - t / 7.0f);
    if (with_intensity) {
      cloud.add(p, t * 0.37f + 0.01f);
    } else {
      cloud.add(p);
    }
  }
  return cloud;
}

// Lengths at which to cut a file in the truncation tests: every byte through
// the header, then an odd stride so cuts land at all offsets within a record.
inline std::size_t truncationStep(std::size_t length) { return length < 400 ? 1 : 7; }

inline bool toolInstalled(const std::string& tool) { return runCommand("command -v " + tool).exit_code == 0; }

}  // namespace hba::test
