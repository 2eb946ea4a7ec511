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

void warnOncePerFolder(const std::filesystem::path& path, const std::string& problem,
                       const std::string& sentence) {
  static std::mutex mutex;
  static std::set<std::pair<std::string, std::string>> warned;  // problem and folder
  const std::lock_guard<std::mutex> lock(mutex);
  if (!warned.insert({problem, path.parent_path().string()}).second) return;
  spdlog::warn("{}: {} (any other file of this folder like it is read alike, without a word more)",
               path.string(), sentence);
}

}  // namespace hba::io
