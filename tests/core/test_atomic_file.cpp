#include <gtest/gtest.h>

#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::size_t countEntries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(AtomicFile, WritesContentAndLeavesNoTemporary) {
  test::TempDir dir;
  writeFileAtomically(dir / "out.txt", [](std::ostream& os) { os << "hello"; });
  EXPECT_EQ(test::readText(dir / "out.txt"), "hello");
  EXPECT_EQ(countEntries(dir.path()), 1u);
}

TEST(AtomicFile, ReplacesExistingFileOnlyOnCommit) {
  test::TempDir dir;
  test::writeText(dir / "out.txt", "old");
  {
    AtomicFile file(dir / "out.txt");
    file.stream() << "new";
    EXPECT_EQ(test::readText(dir / "out.txt"), "old");
    file.commit();
  }
  EXPECT_EQ(test::readText(dir / "out.txt"), "new");
}

TEST(AtomicFile, AbandonedWriteLeavesTargetUntouched) {
  test::TempDir dir;
  test::writeText(dir / "out.txt", "old");
  try {
    writeFileAtomically(dir / "out.txt", [](std::ostream& os) {
      os << "partial";
      throw std::runtime_error("interrupted");
    });
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(test::readText(dir / "out.txt"), "old");
  EXPECT_EQ(countEntries(dir.path()), 1u);
}

TEST(AtomicFile, MissingFolderIsAClearError) {
  test::TempDir dir;
  try {
    writeFileAtomically(dir / "no_such_dir" / "out.txt", [](std::ostream& os) { os << "x"; });
    FAIL() << "expected hba::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_dir"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

}  // namespace
}  // namespace hba
