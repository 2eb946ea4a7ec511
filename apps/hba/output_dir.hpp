#pragma once
#include <filesystem>

#include "hba/io/dataset.hpp"

namespace hba::cli {

// Throws hba::Error if `output` (a file or folder to be written) is the
// dataset's folder, its scans folder, or anything inside them.
void refuseOutputInsideInput(const std::filesystem::path& output, const io::Dataset& dataset);

// Creates the output folder of a command that reads `dataset`. Refuses a
// folder inside the dataset's folders: hba never writes into its input.
// Throws hba::Error.
std::filesystem::path prepareOutputDir(const std::filesystem::path& output,
                                       const io::Dataset& dataset);

}  // namespace hba::cli
