#include "output_dir.hpp"

#include <array>
#include <string>

#include "hba/core/error.hpp"

namespace hba::cli {
namespace fs = std::filesystem;

namespace {

std::vector<fs::path>& recordedInputs() {
  static std::vector<fs::path> inputs;
  return inputs;
}

bool isOutputOption(const CLI::Option& option) {
  static const std::array<const char*, 3> names = {"output", "json", "plot"};
  for (const char* name : names) {
    if (option.check_lname(name)) return true;
  }
  return false;
}

}  // namespace

void recordRunInputs(const CLI::App& command) {
  std::vector<fs::path>& inputs = recordedInputs();
  inputs.clear();
  for (const CLI::Option* option : command.get_options()) {
    if (isOutputOption(*option)) continue;
    for (const std::string& value : option->results()) {
      std::error_code ec;
      if (!value.empty() && fs::exists(value, ec)) inputs.emplace_back(value);
    }
  }
}

const std::vector<fs::path>& runInputs() { return recordedInputs(); }

std::vector<fs::path> namedOutputs(const CLI::App& command) {
  std::vector<fs::path> outputs;
  for (const CLI::Option* option : command.get_options()) {
    if (!isOutputOption(*option)) continue;
    for (const std::string& value : option->results()) {
      if (!value.empty()) outputs.emplace_back(value);
    }
  }
  return outputs;
}

void refuseOutputInsideInput(const fs::path& output, const io::Dataset& dataset) {
  if (dataset.recording() && isSameOrInside(output, dataset.root())) {
    failAt(output, "is the input recording " + dataset.root().string() +
                       " or inside it; choose an output elsewhere (hba never writes into its input)");
  }
  for (const fs::path& input : {dataset.root(), dataset.scansDir(), dataset.posesFile()}) {
    if (!input.empty() && isSameOrInside(output, input)) {
      failAt(output, "is inside the input folder " + input.string() +
                         "; choose an output outside the dataset (hba never writes into its input)");
    }
  }
  refuseReplacingInputs(output);
}

void refuseReplacingInputs(const fs::path& output) {
  for (const fs::path& input : runInputs()) {
    if (!isSameOrInside(input, output)) continue;
    std::error_code ec;
    if (fs::equivalent(input, output, ec)) {
      failAt(output,
             "is an input of this run; write the output to another file (hba never replaces its input)");
    }
    failAt(output, "holds " + input.string() +
                       ", an input of this run, and would be replaced whole; choose another output");
  }
}

std::unique_ptr<OutputLock> claimOutputFile(const fs::path& output, bool force) {
  refuseReplacingInputs(output);
  std::error_code ec;
  const fs::file_status status = fs::status(output, ec);
  if (fs::is_directory(status)) failAt(output, "is a folder; name the file to write");
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    failAt(output, "exists and is not a regular file; choose another output");
  }
  const fs::path parent = fs::absolute(output).parent_path();
  if (!fs::is_directory(parent, ec)) failAt(output, "the folder " + parent.string() + " does not exist");
  auto lock = std::make_unique<OutputLock>(output);
  // Checked under the lock: a run that finished meanwhile left its file.
  if (!force && fs::exists(output, ec)) failAt(output, "exists (use --force to replace it)");
  return lock;
}

}  // namespace hba::cli
