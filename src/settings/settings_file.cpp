// The settings as YAML (`--config`, `--print-config`), JSON (report.json) and
// a Markdown table (docs/settings.md), all made from the setting table.
#include "hba/settings/settings_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <map>
#include <optional>
#include <set>

#include "core/input_file.hpp"
#include "hba/core/did_you_mean.hpp"
#include "hba/core/error.hpp"
#include "hba/settings/setting_table.hpp"

namespace hba::settings {
namespace {

// Everything wrong with a settings file's content is the caller's to fix.
[[noreturn]] void bad(const std::string& source, const std::string& problem) {
  throw ValueError(source + ": " + problem);
}

std::string sectionOf(const std::string& key) {
  const auto dot = key.find('.');
  return dot == std::string::npos ? "" : key.substr(0, dot);
}

std::string leafOf(const std::string& key) {
  const auto dot = key.find('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

// The node of `name` ("window", "local.voxel_size"), if the file gives it.
std::optional<YAML::Node> nodeOf(const YAML::Node& root, const std::string& name) {
  const std::string section = sectionOf(name);
  const YAML::Node parent = section.empty() ? root : root[section];
  if (!parent || !parent.IsMap()) return std::nullopt;
  const YAML::Node node = parent[leafOf(name)];
  if (!node) return std::nullopt;
  return node;
}

void rejectUnknownKeys(const YAML::Node& node, const std::set<std::string>& known, const std::string& where,
                       const std::string& source) {
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    if (known.count(key)) continue;
    const std::vector<std::string> names(known.begin(), known.end());
    std::string valid;
    for (const std::string& name : names) valid += (valid.empty() ? "" : ", ") + where + name;
    bad(source, "unknown setting '" + where + key + "'" + didYouMean(key, names) +
                    "; the settings here are " + valid);
  }
}

// yaml-cpp keeps both entries of a key given twice and reads the first: a
// file whose later line looks like it wins. Refused, with both lines.
void rejectRepeatedKeys(const YAML::Node& map, const std::string& where, const std::string& source) {
  std::map<std::string, int> first_line;
  for (const auto& entry : map) {
    if (!entry.first.IsScalar()) continue;  // rejectUnknownKeys names it
    const std::string key = entry.first.Scalar();
    const int line = entry.first.Mark().line + 1;
    const auto [seen, fresh] = first_line.emplace(key, line);
    if (fresh) continue;
    const std::string lines = seen->second == line
                                  ? "both on line " + std::to_string(line)
                                  : "lines " + std::to_string(seen->second) + " and " + std::to_string(line);
    bad(source, "'" + where + key + "' is given twice (" + lines + "); give it once");
  }
}

// Unknown keys are an error (with a "did you mean"), so a typo never passes
// silently; so are the sections that are not maps and keys given twice.
void rejectUnknownNames(const YAML::Node& root, const std::string& source) {
  rejectRepeatedKeys(root, "", source);
  std::set<std::string> top;
  for (const Setting& s : settingTable()) {
    top.insert(sectionOf(s.key).empty() ? s.key : sectionOf(s.key));
    top.insert(s.aliases.begin(), s.aliases.end());
  }
  rejectUnknownKeys(root, top, "", source);
  for (const SettingSection& section : settingSections()) {
    const YAML::Node map = root[section.name];
    if (!map) continue;
    if (!map.IsMap()) bad(source, "'" + section.name + "' must be a map of settings");
    rejectRepeatedKeys(map, section.name + ".", source);
    std::set<std::string> known;
    for (const Setting& s : settingTable()) {
      if (sectionOf(s.key) == section.name) known.insert(leafOf(s.key));
    }
    rejectUnknownKeys(map, known, section.name + ".", source);
  }
}

// The one name `setting` is given under in the file, if any.
std::optional<std::string> givenName(const YAML::Node& root, const Setting& setting,
                                     const std::string& source) {
  std::vector<std::string> given;
  if (nodeOf(root, setting.key)) given.push_back(setting.key);
  for (const std::string& alias : setting.aliases) {
    if (nodeOf(root, alias)) given.push_back(alias);
  }
  if (given.size() > 1) {
    bad(source, "'" + given[0] + "' and '" + given[1] + "' are the same setting; give one");
  }
  if (given.empty()) return std::nullopt;
  return given.front();
}

SettingValue readValue(const YAML::Node& node, const Setting& setting, const std::string& name,
                       const std::string& source) {
  const auto wrong = [&] {
    bad(source, "'" + name + "' has a value of the wrong type; it takes " + rangeText(setting));
  };
  try {
    switch (setting.type) {
      case SettingType::Switch:
        return node.as<bool>();
      case SettingType::Choice:
        return node.as<std::string>();
      case SettingType::Integer:
      case SettingType::Count:
      case SettingType::Real:
        break;
    }
  } catch (const YAML::Exception&) {
    wrong();
  }
  if (!node.IsScalar()) wrong();
  // A whole-number setting is written as one: 10.0 and 1e1 are refused, as
  // yaml-cpp did (Python's window=10.0 too).
  const std::string& scalar = node.Scalar();
  if (setting.type != SettingType::Real && scalar.find_first_of(".eE") != std::string::npos) wrong();
  // The flags' reading: "too large", "not a whole number" said as such;
  // YAML's .inf and .nan read as the flags' inf and nan (not finite).
  std::string text = node.Scalar();
  const bool signed_dot = text.size() > 2 && (text[0] == '+' || text[0] == '-') && text[1] == '.';
  if ((text.size() > 1 && text[0] == '.' && std::isalpha(text[1])) || (signed_dot && std::isalpha(text[2])))
    text.erase(signed_dot ? 1 : 0, 1);
  const ParsedSetting parsed = parseSettingNumber(setting, text);
  if (parsed.problem.empty()) return parsed.value;
  if (parseNumber(text, setting.range, NumberKind::Real).why == "not a number") wrong();
  bad(source, "setting " + name + " " + parsed.problem);
}

nlohmann::json toJson(const SettingValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b;
  if (const long long* i = std::get_if<long long>(&value)) return *i;
  if (const double* d = std::get_if<double>(&value)) return *d;
  return std::get<std::string>(value);
}

// What a line of --print-config or a row of the docs says after the help.
// its flag, and those of the shorthands that set it too.
std::string flagNote(const Setting& s) {
  std::vector<std::string> flags;
  if (!s.flag.empty()) flags.push_back(s.flag);
  for (const Setting& other : settingTable()) {
    for (const std::string& key : other.sets) {
      if (key == s.key && !other.flag.empty()) flags.push_back(other.flag);
    }
  }
  std::string text;
  for (const std::string& flag : flags) text += (text.empty() ? " (" : ", ") + flag;
  return text.empty() ? text : text + ")";
}

std::string yamlLine(const std::string& indent, const Setting& s, const SettingValue& value) {
  std::string text = indent + leafOf(s.key) + ": " + valueText(value);
  if (text.size() < 34) text.resize(34, ' ');
  std::string comment = s.help;
  if (!s.range.zero.empty()) comment += "; 0 = " + s.range.zero;
  return text + "  # " + comment + flagNote(s) + "\n";
}

// The line (1-based) where the document holding `node` starts: its '---'
// marker after the line `after`, or the node's own line when there is none.
int documentStartLine(const std::string& yaml_text, const YAML::Node& node, int after) {
  const int node_line = node.Mark().line + 1;
  int line = 1, marker = 0;
  for (std::size_t start = 0; start < yaml_text.size() && line <= node_line; ++line) {
    if (line > after && yaml_text.compare(start, 3, "---") == 0) marker = line;
    const std::size_t end = yaml_text.find('\n', start);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return marker > 0 ? marker : node_line;
}

// A file of several YAML documents ('---' between them): yaml-cpp's Load
// reads the first and drops the rest without a word, so settings after the
// separator would silently not apply. Refused, naming where the second starts.
YAML::Node onlyDocument(const std::string& yaml_text, const std::string& source) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::Exception& e) {
    bad(source, "not valid YAML (" + std::string(e.what()) + ")");
  }
  // Empty documents (a leading or a trailing '---') hold nothing to lose.
  std::vector<YAML::Node> given;
  for (const YAML::Node& document : documents) {
    if (document && !document.IsNull()) given.push_back(document);
  }
  if (given.size() > 1) {
    bad(source, "holds more than one YAML document: a second starts at line " +
                    std::to_string(documentStartLine(yaml_text, given[1], given[0].Mark().line + 1)) +
                    " ('---'); hba reads the settings from one document: put them together and remove the "
                    "'---' between them");
  }
  return given.empty() ? YAML::Node() : given.front();
}

}  // namespace

void applySettingsYaml(const std::string& yaml_text, const std::string& source, HbaSettings& settings) {
  const YAML::Node root = onlyDocument(yaml_text, source);
  if (!root || root.IsNull()) return;  // an empty file changes nothing
  if (!root.IsMap()) bad(source, "expected a map of settings at the top level");
  try {
    rejectUnknownNames(root, source);
    // Shorthands first, so that a specific key given beside one wins.
    for (const bool shorthands : {true, false}) {
      for (const Setting& setting : settingTable()) {
        if (setting.shorthand() != shorthands) continue;
        const std::optional<std::string> name = givenName(root, setting, source);
        if (!name) continue;
        const SettingValue value = readValue(*nodeOf(root, *name), setting, *name, source);
        try {
          checkSettingValue(setting, value);
        } catch (const Error& e) {
          bad(source, e.what());
        }
        applySetting(setting, value, settings);
      }
    }
  } catch (const YAML::Exception& e) {
    bad(source, "cannot read settings (" + std::string(e.what()) + ")");
  }
}

void applySettingsFile(const std::filesystem::path& path, HbaSettings& settings) {
  applySettingsYaml(readTextFile(path), path.string(), settings);
}

void checkSettings(const HbaSettings& settings) {
  for (const Setting& s : settingTable()) {
    if (s.shorthand()) continue;
    const SettingValue value = s.get(settings);
    checkSettingValue(s, value);
    if (s.below.empty()) continue;
    const SettingValue limit = settingByKey(s.below).get(settings);
    // 0 is automatic: chosen below its limit (window_size.hpp).
    if (std::get<long long>(value) == 0 || std::get<long long>(limit) == 0) continue;
    if (!(std::get<long long>(value) < std::get<long long>(limit))) {
      const Setting& other = settingByKey(s.below);
      throw ValueError("setting " + s.key + " must be below " + s.below + " (" + s.flag + " " +
                       valueText(value) + " >= " + other.flag + " " + valueText(limit) + ")");
    }
  }
}

nlohmann::json settingsToJson(const HbaSettings& settings) {
  nlohmann::json out = nlohmann::json::object();
  for (const Setting& s : settingTable()) {
    if (s.shorthand()) continue;
    const std::string section = sectionOf(s.key);
    nlohmann::json& parent = section.empty() ? out : out[section];
    parent[leafOf(s.key)] = toJson(s.get(settings));
  }
  return out;
}

std::string settingsToYaml(const HbaSettings& settings) {
  std::string out =
      "# hba optimize settings: every one, at its value (hba optimize --print-config).\n"
      "# Read back with --config FILE; flags given on the command line override the file.\n"
      "# Keys named like the flags (iterations for --iterations, voxel for --voxel, ...) are\n"
      "# read too. docs/settings.md lists every setting; docs/pyramid.md explains them.\n";
  for (const Setting& s : settingTable()) {
    if (!s.shorthand() && sectionOf(s.key).empty()) out += yamlLine("", s, s.get(settings));
  }
  for (const SettingSection& section : settingSections()) {
    out += section.name + ":  # " + section.help + "\n";
    for (const Setting& s : settingTable()) {
      if (sectionOf(s.key) == section.name) out += yamlLine("  ", s, s.get(settings));
    }
  }
  return out;
}

std::string settingsMarkdown() {
  std::string out =
      "| YAML key | flag | default | takes | what it sets |\n"
      "|---|---|---|---|---|\n";
  const auto cell = [](const std::string& text) {
    return text.empty() ? std::string("—") : "`" + text + "`";
  };
  for (const Setting& s : settingTable()) {
    std::string key = "`" + s.key + "`";
    for (const std::string& alias : s.aliases) key += " or `" + alias + "`";
    std::string what = s.help;
    std::string fallback;
    if (s.shorthand()) {
      what += "; sets";
      for (const std::string& target : s.sets) what += " `" + target + "`";
      fallback = "as they are";
    } else {
      fallback = valueText(s.default_value);
    }
    out += "| " + key + " | " + cell(s.flag) + " | " + (s.shorthand() ? fallback : "`" + fallback + "`") +
           " | " + rangeText(s) + " | " + what + " |\n";
  }
  return out;
}

}  // namespace hba::settings
