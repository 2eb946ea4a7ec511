#pragma once
// What `hba --version` prints and report.json records: the release and the
// git revision it was built from, so a report names the exact code.
#include <string>

#include "hba/revision.hpp"
#include "hba/version.hpp"

namespace hba::cli {

inline std::string versionText() { return std::string("hba ") + HBA_VERSION + " (git " + HBA_REVISION + ")"; }

}  // namespace hba::cli
