#pragma once
// Size arithmetic on numbers read from files: a header may declare anything,
// so every product and sum is checked and an overflow is reported as a bad
// file instead of wrapping into a small, wrong size.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include "hba/core/error.hpp"

namespace hba::io::detail {

inline std::uint64_t checkedMul(std::uint64_t a, std::uint64_t b, const std::filesystem::path& path,
                                const std::string& what) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
    failAt(path, what + " overflows (" + std::to_string(a) + " x " + std::to_string(b) + ")");
  }
  return a * b;
}

inline std::uint64_t checkedAdd(std::uint64_t a, std::uint64_t b, const std::filesystem::path& path,
                                const std::string& what) {
  if (b > std::numeric_limits<std::uint64_t>::max() - a) {
    failAt(path, what + " overflows (" + std::to_string(a) + " + " + std::to_string(b) + ")");
  }
  return a + b;
}

}  // namespace hba::io::detail
