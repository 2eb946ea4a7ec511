#pragma once
#include <filesystem>

#include "hba/io/dataset.hpp"

namespace hba::cli {

// Throws hba::Error if `output` (a file or folder to be written) is the
// dataset's folder, its scans folder, or anything inside them.
void refuseOutputInsideInput(const std::filesystem::path& output, const io::Dataset& dataset);

// The one output rule, for single files: an existing file is replaced only
// with --force (it is then replaced atomically). Throws hba::Error.
void refuseToReplace(const std::filesystem::path& output, bool force);

}  // namespace hba::cli
