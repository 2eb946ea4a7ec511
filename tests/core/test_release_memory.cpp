#include "core/release_memory.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace hba {
namespace {

// Resident memory of this process (kB), or -1 where /proc is absent.
long residentKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

// 256 MB in 2 kB pieces (below the size the allocator maps on its own),
// freed but for the last piece, which pins the heap's top: without the
// release the pages stay resident; with it they are returned.
TEST(ReleaseFreedMemory, ReturnsTheFreedPiecesOfTheHeap) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "only glibc's allocator returns pages on request";
#endif
#if defined(__SANITIZE_THREAD__)
  // TSan's own allocator serves malloc: glibc's heap, which malloc_trim
  // trims, holds none of these pieces.
  GTEST_SKIP() << "ThreadSanitizer replaces glibc's allocator";
#endif
  if (residentKiB() < 0) GTEST_SKIP() << "no /proc/self/status";
  constexpr std::size_t kPiece = 2048;
  constexpr std::size_t kPieces = (std::size_t{256} << 20) / kPiece;
  std::vector<std::unique_ptr<char[]>> pieces(kPieces);
  for (auto& piece : pieces) {
    piece = std::make_unique<char[]>(kPiece);
    piece[0] = 1;  // touch: resident
  }
  const long full = residentKiB();
  for (std::size_t k = 0; k + 1 < kPieces; ++k) pieces[k].reset();
  const long freed = residentKiB();
  releaseFreedMemory();
  const long released = residentKiB();
  std::printf("resident: %ld kB full, %ld freed, %ld released\n", full, freed, released);
  EXPECT_GT(freed, full - (64L << 10));       // freeing alone keeps most pages
  EXPECT_LT(released, freed - (128L << 10));  // the release returns them
}

}  // namespace
}  // namespace hba
