#pragma once
// A flag that takes one of an enum's names (hba/core/enum_names.hpp), with
// '-' and '_' alike: the names in the help and the check come from the enum.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"

namespace hba::cli {

template <typename E>
CLI::IsMember oneOf() {
  return CLI::IsMember(enumNames<E>(), [](std::string name) { return normalizedEnumName(name); });
}

// One of `names` or an existing file (`file`: what it holds): a typo is a
// usage error at once, not a failure to read "regster" after the first work.
inline CLI::Validator nameOrFile(const std::vector<std::string>& names, const std::string& file) {
  std::string list;
  for (const std::string& name : names) list += name + ", ";
  return CLI::Validator(
      [names, file, list](const std::string& text) -> std::string {
        for (const std::string& name : names) {
          if (text == name) return "";
        }
        if (std::filesystem::is_regular_file(text)) return "";
        return "must be " + list + "or " + file + ", got '" + text + "' (no such file)";
      },
      "NAME|FILE");
}

}  // namespace hba::cli
