#pragma once
// JSON output of the commands. Paths are user text and may hold bytes that are
// not UTF-8 (a folder named with 0xff): nlohmann's dump() throws on them, which
// failed a finished run at its last step. Such bytes become U+FFFD instead.
#include <nlohmann/json.hpp>
#include <string>

namespace hba::cli {

inline std::string jsonText(const nlohmann::json& value, int indent = -1) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace hba::cli
