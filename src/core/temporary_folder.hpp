#pragma once
// Where hba keeps scratch files (kept clouds, self-check maps).
#include <filesystem>

namespace hba {

// $TMPDIR when set and not empty (POSIX), else /tmp. Throws hba::Error naming
// the folder and TMPDIR when it is not a folder, so a mistyped TMPDIR is
// reported with its value, not as a bare "No such file or directory".
std::filesystem::path temporaryFolder();

}  // namespace hba
