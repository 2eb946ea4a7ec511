// Scan reading speed against a plain std::fread of the same bytes, on a
// Livox/Velodyne-sized scan (120k points with intensity) written by the
// benchmark into a temporary folder. The files stay in the page cache, so
// the plain read is the floor and the ratio shows what decoding costs.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hba/io/kitti_bin.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"

namespace {
namespace fs = std::filesystem;

constexpr std::size_t kScanPoints = 120000;

// A scan-like cloud: points on walls and ground at 1-60 m, intensities 0-255.
hba::PointCloud makeScan() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  hba::PointCloud cloud;
  cloud.reserve(kScanPoints, true);
  for (std::size_t i = 0; i < kScanPoints; ++i) {
    const float azimuth = 6.2831853f * unit(rng);
    const float range = 1.0f + 59.0f * unit(rng);
    const float height = -1.8f + 4.0f * unit(rng);
    cloud.add(hba::Vec3f(range * std::cos(azimuth), range * std::sin(azimuth), height),
              std::floor(255.0f * unit(rng)));
  }
  return cloud;
}

// The scan in every format, written once per process and removed at exit.
struct ScanFiles {
  fs::path dir = fs::temp_directory_path() / ("hba_bench_io_" + std::to_string(::getpid()));
  ScanFiles() {
    fs::create_directories(dir);
    const hba::PointCloud scan = makeScan();
    hba::io::writePcd(dir / "binary.pcd", scan, hba::io::PcdEncoding::Binary);
    hba::io::writePcd(dir / "compressed.pcd", scan, hba::io::PcdEncoding::BinaryCompressed);
    hba::io::writePcd(dir / "ascii.pcd", scan, hba::io::PcdEncoding::Ascii);
    hba::io::writeKittiBin(dir / "scan.bin", scan);
    hba::io::writePly(dir / "binary.ply", scan);
  }
  ~ScanFiles() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  fs::path operator/(const char* name) const { return dir / name; }
};

const ScanFiles& files() {
  static const ScanFiles instance;
  return instance;
}

// The floor: one fread of the whole file into a buffer, nothing decoded.
std::size_t plainRead(const fs::path& path) {
  const std::size_t size = fs::file_size(path);
  std::unique_ptr<char[]> buffer(new char[size]);
  std::FILE* file = std::fopen(path.c_str(), "rb");
  const std::size_t got = std::fread(buffer.get(), 1, size, file);
  std::fclose(file);
  benchmark::DoNotOptimize(buffer.get());
  return got;
}

template <typename Read>
void runRead(benchmark::State& state, const char* name, Read read) {
  const fs::path path = files() / name;
  const auto bytes = static_cast<std::int64_t>(fs::file_size(path));
  for (auto _ : state) benchmark::DoNotOptimize(read(path));
  state.SetBytesProcessed(state.iterations() * bytes);
  state.counters["points"] = static_cast<double>(kScanPoints);
}

void BM_PlainFread_PcdBinary(benchmark::State& s) { runRead(s, "binary.pcd", plainRead); }
void BM_ReadPcd_Binary(benchmark::State& s) { runRead(s, "binary.pcd", hba::io::readPcd); }
void BM_PlainFread_KittiBin(benchmark::State& s) { runRead(s, "scan.bin", plainRead); }
void BM_ReadKittiBin(benchmark::State& s) { runRead(s, "scan.bin", hba::io::readKittiBin); }
void BM_ReadPly_Binary(benchmark::State& s) { runRead(s, "binary.ply", hba::io::readPly); }
void BM_PlainFread_PcdCompressed(benchmark::State& s) { runRead(s, "compressed.pcd", plainRead); }
void BM_ReadPcd_BinaryCompressed(benchmark::State& s) { runRead(s, "compressed.pcd", hba::io::readPcd); }
void BM_ReadPcd_Ascii(benchmark::State& s) { runRead(s, "ascii.pcd", hba::io::readPcd); }
// What `hba info` pays per scan: the header alone (time only, no MB/s).
void BM_ReadPcdHeader(benchmark::State& state) {
  const fs::path path = files() / "binary.pcd";
  for (auto _ : state) benchmark::DoNotOptimize(hba::io::readPcdHeader(path));
}

BENCHMARK(BM_PlainFread_PcdBinary)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReadPcd_Binary)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlainFread_KittiBin)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReadKittiBin)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReadPly_Binary)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlainFread_PcdCompressed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReadPcd_BinaryCompressed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReadPcd_Ascii)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReadPcdHeader)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
