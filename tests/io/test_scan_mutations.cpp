// Robustness: real fixtures with random bytes overwritten, and pure noise,
// must either read or throw hba::Error naming the file (run under
// AddressSanitizer to also prove no read leaves its buffer).
#include <gtest/gtest.h>

#include <random>

#include "hba/io/las.hpp"
#include "hba/io/scan_file.hpp"
#include "test_las_bytes.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

void expectReadOrCleanError(const fs::path& path) {
  try {
    readScan(path);
  } catch (const Error& error) {
    ASSERT_EQ(std::string(error.what()).rfind(path.string() + ": ", 0), 0u) << error.what();
  }
}

TEST(ScanMutations, FixturesWithRandomBytesChangedNeverCrash) {
  // LAS has no checked-in fixture: one written by hba, one made by hand
  // (LAS 1.2 with a VLR and longer records).
  test::TempDir las_dir;
  writeLas(las_dir / "hba.las", test::makeCloud(200, true));
  test::LasSpec spec;
  spec.vlr_payloads = {24};
  spec.record_length = 31;
  std::vector<test::LasPointInts> points;
  for (int i = 0; i < 200; ++i) points.push_back({i * 13, -i * 7, i * i, static_cast<std::uint16_t>(i)});
  test::writeText(las_dir / "made_1_2.las", test::lasBytes(spec, points));
  const fs::path fixtures[] = {las_dir / "hba.las",
                               las_dir / "made_1_2.las",
                               test::pcdFixture("hku1_cut_ascii.pcd"),
                               test::pcdFixture("hku1_cut_binary.pcd"),
                               test::pcdFixture("hku1_cut_binary_compressed.pcd"),
                               test::pcdFixture("fpfh_binary_compressed.pcd"),
                               test::plyFixture("mesh_binary.ply"),
                               test::plyFixture("hku1_cut_ascii.ply"),
                               test::binFixture("hku1_cut.bin")};
  std::mt19937 rng(12345);
  test::TempDir dir;
  for (const fs::path& fixture : fixtures) {
    SCOPED_TRACE(fixture.filename().string());
    const std::string original = test::readText(fixture);
    // Most damage goes to the header and the first records, where sizes live.
    std::uniform_int_distribution<std::size_t> near_start(0, std::min<std::size_t>(original.size(), 400) - 1);
    std::uniform_int_distribution<std::size_t> anywhere(0, original.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int trial = 0; trial < 150; ++trial) {
      std::string mutated = original;
      for (int k = 0; k < 1 + trial % 4; ++k) {
        mutated[trial % 2 ? near_start(rng) : anywhere(rng)] = static_cast<char>(byte(rng));
      }
      const fs::path path = dir / (std::to_string(trial) + fixture.extension().string());
      test::writeText(path, mutated);
      expectReadOrCleanError(path);
    }
  }
}

TEST(ScanMutations, NoiseNeverCrashes) {
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> byte(0, 255);
  test::TempDir dir;
  for (int trial = 0; trial < 60; ++trial) {
    std::string noise(static_cast<std::size_t>(trial * 37), '\0');
    for (char& c : noise) c = static_cast<char>(byte(rng));
    for (const char* extension : {".pcd", ".ply", ".bin", ".las", ".xyz"}) {
      const fs::path path = dir / (std::to_string(trial) + extension);
      test::writeText(path, noise);
      expectReadOrCleanError(path);
    }
  }
}

}  // namespace
}  // namespace hba::io
