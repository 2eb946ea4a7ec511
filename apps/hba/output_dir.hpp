#pragma once
#include <filesystem>

#include "hba/io/dataset.hpp"

namespace hba::cli {

// Creates the output folder of a command that reads `dataset`. Refuses a
// folder inside the dataset's folders: hba never writes into its input.
// Throws hba::Error.
std::filesystem::path prepareOutputDir(const std::filesystem::path& output,
                                       const io::Dataset& dataset);

}  // namespace hba::cli
