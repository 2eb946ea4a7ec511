#pragma once
// Range checks for numeric flags whose messages read like a sentence
// (CLI11's own print the range's ends: 300 digits for "no upper bound").
#include <CLI/CLI.hpp>
#include <string>

namespace hba::cli {

// "must be >= 0" / "must be > 0", or CLI11's parse error for a non-number.
inline CLI::Validator nonNegative() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
        return value >= 0.0 ? "" : "must be >= 0, got " + text;
      },
      "NONNEGATIVE");
}

inline CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
        return value > 0.0 ? "" : "must be > 0, got " + text;
      },
      "POSITIVE");
}

}  // namespace hba::cli
