#pragma once
#include <filesystem>

namespace hba {

// True if `inner` is `outer` or lies inside it, symbolic links resolved
// (paths that do not exist yet are compared as far as they do).
bool isSameOrInside(const std::filesystem::path& inner, const std::filesystem::path& outer);

}  // namespace hba
