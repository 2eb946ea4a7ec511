#include "io/file_warnings.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <mutex>
#include <set>
#include <utility>

namespace hba::io {

void warnAboutFile(const std::filesystem::path& path, const std::string& problem,
                   const std::string& sentence) {
  static std::mutex mutex;
  // problem and folder -> the files warned about
  static std::map<std::pair<std::string, std::string>, std::set<std::string>> warned;
  const std::lock_guard<std::mutex> lock(mutex);
  const std::string folder = path.parent_path().string();
  std::set<std::string>& files = warned[{problem, folder}];
  if (!files.insert(path.filename().string()).second) return;
  if (files.size() <= kNamedFilesPerProblem) {
    spdlog::warn("{}: {}", path.string(), sentence);
  } else if (files.size() == kNamedFilesPerProblem + 1) {
    spdlog::warn("{}: more files in this folder have the same problem ({}); hba names no more of them",
                 folder.empty() ? "." : folder, problem);
  }
}

}  // namespace hba::io
