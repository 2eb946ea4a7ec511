#pragma once
// What a folder holds: every file's relative path with a hash of its bytes,
// to prove a command left its input exactly as it was.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace hba::test {

using FolderSnapshot = std::map<std::string, std::uint64_t>;  // relative path -> content hash

FolderSnapshot snapshotFolder(const std::filesystem::path& root);

}  // namespace hba::test
