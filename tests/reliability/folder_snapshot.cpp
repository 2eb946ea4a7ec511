#include "folder_snapshot.hpp"

#include <system_error>

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
    // Lexically: fs::relative resolves links, and throws on a loop.
    const std::string relative = entry.path().lexically_relative(root).string();
    // Folders count too (an added empty folder is a write into the input);
    // a link by where it points and what it leads to (it may lead nowhere,
    // or into a loop: no exception for those).
    std::error_code ec;
    const std::string link = entry.is_symlink(ec) ? "->" + fs::read_symlink(entry.path(), ec).string() : "";
    const bool file = entry.is_regular_file(ec);
    snapshot[relative] = file || !link.empty() ? contentHash(link + (file ? readText(entry.path()) : "")) : 0;
  }
  return snapshot;
}

}  // namespace hba::test
