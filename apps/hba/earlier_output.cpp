#include "earlier_output.hpp"

#include "core/input_file.hpp"
#include "hba/core/error.hpp"
#include "pyramid/output_report.hpp"

namespace hba::cli {

bool isOptimizeOutput(const std::filesystem::path& folder) {
  return regularFileIsPresent(folder / "report.json") && regularFileIsPresent(folder / "pose.json");
}

nlohmann::json readOutputReport(const std::filesystem::path& folder) {
  if (!isOptimizeOutput(folder))
    failAt(folder, "is not an hba optimize output (no report.json and pose.json)");
  return pyramid::parseOutputReport(readTextFile(folder / "report.json"), folder / "report.json");
}

std::string outputInput(const nlohmann::json& report, const std::filesystem::path& folder, const char* key) {
  return pyramid::reportInputText(report, folder / "report.json", key);
}

bool outputInputFlag(const nlohmann::json& report, const std::filesystem::path& folder, const char* key) {
  return pyramid::reportInputFlag(report, folder / "report.json", key);
}

}  // namespace hba::cli
