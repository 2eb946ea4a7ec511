#include "output_dir.hpp"

#include "hba/core/error.hpp"

namespace hba::cli {
namespace fs = std::filesystem;

namespace {

bool isInside(const fs::path& path, const fs::path& folder) {
  const fs::path p = fs::weakly_canonical(path);
  const fs::path f = fs::weakly_canonical(folder);
  auto pi = p.begin();
  for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
    if (fi->empty()) continue;  // a trailing separator
    if (pi == p.end() || *pi != *fi) return false;
  }
  return true;
}

}  // namespace

void refuseOutputInsideInput(const fs::path& output, const io::Dataset& dataset) {
  for (const fs::path& input : {dataset.root(), dataset.scansDir(), dataset.posesFile()}) {
    if (!input.empty() && isInside(output, input)) {
      failAt(output, "is inside the input folder " + input.string() +
                         "; choose an output outside the dataset (hba never writes into its input)");
    }
  }
}

void refuseToReplace(const fs::path& output, bool force) {
  std::error_code ec;
  if (!force && fs::exists(output, ec)) failAt(output, "exists (use --force to replace it)");
}

}  // namespace hba::cli
