#pragma once
// The dataset arguments shared by every command that reads a sequence:
// DIR plus the overrides --scans, --poses and --format.
#include <CLI/CLI.hpp>
#include <string>

#include "hba/io/dataset.hpp"

namespace hba::cli {

struct DatasetArgs {
  std::string dir;
  std::string scans;
  std::string poses;
  std::string format;

  // Adds the positional DIR and the override flags to `command`.
  void addTo(CLI::App* command);
  // Discovers the dataset (overrides win). Throws hba::Error.
  io::Dataset open() const;
};

}  // namespace hba::cli
