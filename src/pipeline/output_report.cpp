#include "pipeline/output_report.hpp"

#include "hba/core/error.hpp"

namespace hba::pipeline {

nlohmann::json parseOutputReport(const std::string& text, const std::filesystem::path& file) {
  nlohmann::json report = nlohmann::json::parse(text, nullptr, false);
  if (report.is_discarded()) failAt(file, "is not readable JSON");
  return report;
}

namespace {

// The input section's field `key`, or null when the report has none.
const nlohmann::json* inputField(const nlohmann::json& report, const char* key) {
  if (!report.is_object()) return nullptr;
  const auto input = report.find("input");
  if (input == report.end() || !input->is_object()) return nullptr;
  const auto field = input->find(key);
  return field == input->end() ? nullptr : &*field;
}

}  // namespace

std::string reportInputText(const nlohmann::json& report, const std::filesystem::path& file,
                            const char* key) {
  const nlohmann::json* field = inputField(report, key);
  if (!field || !field->is_string())
    failAt(file, std::string("has no input.") + key + " (not written by hba optimize?)");
  return field->get<std::string>();
}

bool reportInputFlag(const nlohmann::json& report, const std::filesystem::path& file, const char* key) {
  const nlohmann::json* field = inputField(report, key);
  if (!field) return false;
  if (!field->is_boolean()) {
    failAt(file, std::string("input.") + key + " is a " + field->type_name() +
                     ", not true or false (not written by hba optimize?)");
  }
  return field->get<bool>();
}

}  // namespace hba::pipeline
