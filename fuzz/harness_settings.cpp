// The settings harness, apart from the parsers': it links the whole pyramid.
#include <fstream>
#include <sstream>
#include <string>

#include "harness.hpp"
#include "hba/core/error.hpp"
#include "hba/settings/settings_file.hpp"

namespace hba::fuzz {
namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& input) {
  std::ifstream in(input, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

// As `hba optimize --config` does: parse, range-check, echo as JSON.
void feedSettingsYaml(const fs::path& input) {
  const std::string text = readAll(input);
  try {
    HbaSettings settings;
    settings::applySettingsYaml(text, "fuzz.yaml", settings);
    settings::checkSettings(settings);
    settings::settingsToJson(settings).dump();
  } catch (const Error&) {
    // The documented outcome for a bad settings file.
  }
}

}  // namespace hba::fuzz
