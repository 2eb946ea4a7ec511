#pragma once
// report.json read back (`hba view OUT`, `hba optimize --map OUT`): the
// parse and the fields of its `input` section the commands use, apart from
// the command line so the fuzzer (fuzz_report_json) reaches them. Every
// problem throws hba::Error naming `file`, never a JSON library exception.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace hba::pipeline {

// The report's text as JSON: "<file>: is not readable JSON" when it is not.
nlohmann::json parseOutputReport(const std::string& text, const std::filesystem::path& file);

// A text field of the report's `input` section ("dataset", "poses",
// "pose_frame"): "<file>: has no input.<key> (not written by hba optimize?)"
// when it is missing or not text.
std::string reportInputText(const nlohmann::json& report, const std::filesystem::path& file, const char* key);

// A true/false field of the `input` section ("scans_in_world"); false when
// absent; "<file>: input.<key> is a string, not true or false (not written
// by hba optimize?)" when another value.
bool reportInputFlag(const nlohmann::json& report, const std::filesystem::path& file, const char* key);

}  // namespace hba::pipeline
