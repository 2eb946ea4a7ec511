// What hba writes, PCL reads (and the other way round): run only where the
// Debian pcl-tools are installed; the fixture-based tests cover the rest.
#include <gtest/gtest.h>

#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

std::string quotedPath(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

TEST(PclInterop, PclReadsEveryPcdEncodingHbaWrites) {
  if (!test::toolInstalled("pcl_convert_pcd_ascii_binary")) GTEST_SKIP() << "pcl-tools not installed";
  test::TempDir dir;
  const PointCloud cloud = test::makeCloud(300, true);
  for (const PcdEncoding encoding :
       {PcdEncoding::Ascii, PcdEncoding::Binary, PcdEncoding::BinaryCompressed}) {
    SCOPED_TRACE(static_cast<int>(encoding));
    writePcd(dir / "ours.pcd", cloud, encoding);
    // PCL re-encodes as binary (exact) and as 9-digit ascii (exact for float).
    for (const char* mode : {"1", "0"}) {
      const test::CommandResult result =
          test::runCommand("pcl_convert_pcd_ascii_binary " + quotedPath(dir / "ours.pcd") + " " +
                           quotedPath(dir / "pcl.pcd") + " " + mode + " 9");
      ASSERT_EQ(result.exit_code, 0) << result.output;
      test::expectSameCloud(cloud, readPcd(dir / "pcl.pcd"));
    }
  }
}

TEST(PclInterop, PclReadsThePlyHbaWrites) {
  if (!test::toolInstalled("pcl_ply2pcd")) GTEST_SKIP() << "pcl-tools not installed";
  test::TempDir dir;
  const PointCloud cloud = test::makeCloud(300, true);
  for (const PlyEncoding encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian}) {
    writePly(dir / "ours.ply", cloud, encoding);
    const test::CommandResult result = test::runCommand(
        "pcl_ply2pcd -format 1 " + quotedPath(dir / "ours.ply") + " " + quotedPath(dir / "pcl.pcd"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    test::expectSameCloud(cloud, readPcd(dir / "pcl.pcd"));
  }
}

}  // namespace
}  // namespace hba::io
