#include "folder_snapshot.hpp"

#include "test_support.hpp"

namespace hba::test {
namespace fs = std::filesystem;

namespace {

// FNV-1a: enough to tell a changed file from an unchanged one.
std::uint64_t contentHash(const std::string& bytes) {
  std::uint64_t hash = 1469598103934665603ull;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace

FolderSnapshot snapshotFolder(const fs::path& root) {
  FolderSnapshot snapshot;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    const std::string relative = fs::relative(entry.path(), root).string();
    // Folders count too (an added empty folder is a write into the input).
    snapshot[relative] = entry.is_regular_file() ? contentHash(readText(entry.path())) : 0;
  }
  return snapshot;
}

}  // namespace hba::test
