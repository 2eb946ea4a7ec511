#include "core/temporary_folder.hpp"

#include <cstdlib>
#include <string>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"

namespace hba {

std::filesystem::path temporaryFolder() {
  const char* value = std::getenv("TMPDIR");
  const bool from_environment = value != nullptr && *value != '\0';
  const std::filesystem::path folder = from_environment ? value : "/tmp";
  try {
    requireFolder(folder, "temporary folder");
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + (from_environment
                                             ? " (TMPDIR names it; set TMPDIR to a folder hba can write in)"
                                             : " (TMPDIR is not set; set it to a folder hba can write in)"));
  }
  return folder;
}

}  // namespace hba
