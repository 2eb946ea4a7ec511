#include "earlier_output.hpp"

#include "core/input_file.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

bool isOptimizeOutput(const std::filesystem::path& folder) {
  return regularFileIsPresent(folder / "report.json") && regularFileIsPresent(folder / "pose.json");
}

nlohmann::json readOutputReport(const std::filesystem::path& folder) {
  if (!isOptimizeOutput(folder))
    failAt(folder, "is not an hba optimize output (no report.json and pose.json)");
  const nlohmann::json report = nlohmann::json::parse(readTextFile(folder / "report.json"), nullptr, false);
  if (report.is_discarded()) failAt(folder / "report.json", "is not readable JSON");
  return report;
}

std::string outputInput(const nlohmann::json& report, const std::filesystem::path& folder, const char* key) {
  const auto input = report.find("input");
  if (input == report.end() || !input->is_object() || !input->contains(key) || !(*input)[key].is_string())
    failAt(folder / "report.json", std::string("has no input.") + key + " (not written by hba optimize?)");
  return (*input)[key].get<std::string>();
}

}  // namespace hba::cli
