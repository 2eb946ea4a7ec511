#pragma once
// Paths and small helpers shared by the tests.
#include <filesystem>
#include <map>
#include <string>

namespace hba::test {

// tests/data in the source tree (checked-in fixtures).
std::filesystem::path dataDir();
// ../shared/data beside the repository (real sequences); may be absent.
std::filesystem::path sharedDataDir();
// The built `hba` command-line tool.
std::filesystem::path cliPath();

// A fresh empty directory, removed with its content when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};
// Runs a shell command and captures its output.
CommandResult runCommand(const std::string& command);

// Writes `content` to `path` verbatim (for hand-made corrupt inputs).
void writeText(const std::filesystem::path& path, const std::string& content);
std::string readText(const std::filesystem::path& path);
// Relative path -> bytes of every regular file under `root` but hba's
// output marker.
std::map<std::string, std::string> fileContents(const std::filesystem::path& root);

}  // namespace hba::test
