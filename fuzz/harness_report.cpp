// report.json read back as `hba view OUT` and `hba optimize --map OUT` read
// it: parsed, the input section's fields taken, the whole embedded in the
// report page (dumped as the page does).
#include <fstream>
#include <sstream>
#include <string>

#include "harness.hpp"
#include "harness_checks.hpp"
#include "pipeline/output_report.hpp"

namespace hba::fuzz {
namespace fs = std::filesystem;

void feedReportJson(const fs::path& input) {
  std::ifstream in(input, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  nlohmann::json report;
  try {
    report = pipeline::parseOutputReport(text.str(), "report.json");
  } catch (const Error&) {
    return;
  }
  // hba view refuses a run of several sessions or against a map.
  static_cast<void>(report.contains("sessions") || report.contains("map"));
  for (const char* key : {"dataset", "poses", "pose_format", "pose_frame"}) {
    rejectOnlyWithError([&] { pipeline::reportInputText(report, "report.json", key); });
  }
  rejectOnlyWithError([&] { pipeline::reportInputFlag(report, "report.json", "scans_in_world"); });
  // As the page embeds it (render/report_page.cpp, scriptJson).
  nlohmann::json header = {{"report", report}};
  static_cast<void>(header.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

}  // namespace hba::fuzz
