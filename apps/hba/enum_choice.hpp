#pragma once
// A flag that takes one of an enum's names (hba/core/enum_names.hpp), with
// '-' and '_' alike: the names in the help and the check come from the enum.
#include <CLI/CLI.hpp>

#include "hba/core/enum_names.hpp"

namespace hba::cli {

template <typename E>
CLI::IsMember oneOf() {
  return CLI::IsMember(enumNames<E>(), [](std::string name) { return normalizedEnumName(name); });
}

}  // namespace hba::cli
