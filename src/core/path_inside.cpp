#include "core/path_inside.hpp"

namespace hba {
namespace fs = std::filesystem;

bool isSameOrInside(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path i = fs::weakly_canonical(inner, ec);
  const fs::path o = fs::weakly_canonical(outer, ec);
  auto ii = i.begin();
  for (auto oi = o.begin(); oi != o.end(); ++oi, ++ii) {
    if (oi->empty()) continue;  // a trailing separator
    if (ii == i.end() || *ii != *oi) return false;
  }
  return true;
}

}  // namespace hba
