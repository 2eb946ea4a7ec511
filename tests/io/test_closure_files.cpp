// The closure stage's input files: loop pairs and position priors.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "hba/core/error.hpp"
#include "hba/io/loop_file.hpp"
#include "hba/io/position_prior_file.hpp"
#include "test_support.hpp"

namespace hba::io {
namespace {

using test::TempDir;
using test::writeText;

std::string errorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LoopFile, ReadsPairsWithAndWithoutARelativePose) {
  TempDir dir;
  writeText(dir / "loops.txt",
            "# i j [tx ty tz qx qy qz qw]\n3 40\n41 5 1 2 3 0 0 0.7071067811865476 0.7071067811865476\n");
  const auto loops = readLoopFile(dir / "loops.txt", 50);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].from, 3u);
  EXPECT_EQ(loops[0].to, 40u);
  EXPECT_FALSE(loops[0].relative);
  EXPECT_EQ(loops[1].from, 41u);
  EXPECT_EQ(loops[1].to, 5u);
  ASSERT_TRUE(loops[1].relative);
  EXPECT_TRUE(loops[1].relative->t.isApprox(Vec3(1, 2, 3)));
  // 90 degrees about z: x goes to y.
  EXPECT_TRUE((loops[1].relative->q * Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-12));
  EXPECT_EQ(loops[1].line, 3u);
}

TEST(LoopFile, NamesTheFileAndLineOfEveryProblem) {
  TempDir dir;
  const auto problem = [&](const std::string& text) {
    writeText(dir / "loops.txt", text);
    return errorOf([&] { readLoopFile(dir / "loops.txt", 50); });
  };
  EXPECT_NE(problem("1 2 3\n").find("line 1: expected 2 numbers"), std::string::npos);
  EXPECT_NE(problem("1 2\n1 50\n").find("line 2: second frame 50 is beyond the sequence (50 frames"),
            std::string::npos);
  // Found by fuzz_loop_file: an index beyond any integer type is named as written (it was cast to
  // long long for the message: undefined, "-9223372036854775808" on x86).
  EXPECT_NE(problem("1 2e33\n").find("line 1: second frame 2e+33 is beyond the sequence (50 frames"),
            std::string::npos);
  EXPECT_NE(problem("1.5 2\n").find("whole number"), std::string::npos);
  EXPECT_NE(problem("-1 2\n").find("whole number"), std::string::npos);
  EXPECT_NE(problem("7 7\n").find("with itself"), std::string::npos);
  EXPECT_NE(problem("1 2 0 0 0 0 0 0 0\n").find("line 1"), std::string::npos);  // zero quaternion
  EXPECT_NE(problem("").find("loops.txt"), std::string::npos);
  EXPECT_NE(errorOf([&] { readLoopFile(dir / "missing.txt", 5); }).find("missing.txt"), std::string::npos);
}

TEST(PositionPriorFile, ReadsOneOrThreeSigmas) {
  TempDir dir;
  writeText(dir / "gnss.txt", "# t x y z sigma\n10.0 1 2 3 0.5\n10.5 4 5 6 0.3 0.4 2.0\n");
  const auto priors = readPositionPriorFile(dir / "gnss.txt");
  ASSERT_EQ(priors.size(), 2u);
  EXPECT_DOUBLE_EQ(priors[0].stamp, 10.0);
  EXPECT_TRUE(priors[0].position.isApprox(Vec3(1, 2, 3)));
  EXPECT_TRUE(priors[0].sigma.isApprox(Vec3::Constant(0.5)));
  EXPECT_TRUE(priors[1].sigma.isApprox(Vec3(0.3, 0.4, 2.0)));
}

TEST(PositionPriorFile, NamesTheFileAndLineOfEveryProblem) {
  TempDir dir;
  const auto problem = [&](const std::string& text) {
    writeText(dir / "gnss.txt", text);
    return errorOf([&] { readPositionPriorFile(dir / "gnss.txt"); });
  };
  EXPECT_NE(problem("1 2 3 4\n").find("line 1: expected 5 numbers"), std::string::npos);
  EXPECT_NE(problem("1 2 3 4 0\n").find("line 1: sigma must be positive"), std::string::npos);
  EXPECT_NE(problem("1 2 3 4 1 1 -1\n").find("sigma must be positive"), std::string::npos);
  EXPECT_NE(problem("2 0 0 0 1\n2 0 0 0 1\n").find("line 2: stamps must increase"), std::string::npos);
  EXPECT_NE(problem("2 0 0 0 1\n1 0 0 0 1\n").find("gnss.txt: line 2"), std::string::npos);
}

}  // namespace
}  // namespace hba::io
