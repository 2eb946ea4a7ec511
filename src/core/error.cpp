#include "hba/core/error.hpp"

namespace hba {

void failAt(const std::filesystem::path& path, const std::string& problem) {
  throw Error(path.string() + ": " + problem);
}

}  // namespace hba
