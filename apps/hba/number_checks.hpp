#pragma once
// Range checks for numeric flags, in the settings' wording (number_range.hpp):
// "--radius: must be (0, 10] m, got inf (not finite)". CLI11 puts the flag's
// name in front and hba exits 2. Every numeric flag has one: no flag takes
// inf, nan, or a value no run could use.
#include <CLI/CLI.hpp>
#include <charconv>
#include <cstdint>
#include <string>

#include "hba/core/number_range.hpp"

namespace hba::cli {

// `unit` follows the range in the message ("m", "s").
inline CLI::Validator numberIn(const NumberRange& range, NumberKind kind = NumberKind::Real,
                               const std::string& unit = "") {
  const std::string range_text = rangeText(range) + (unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [range, kind, range_text](std::string& text) {
        const std::string problem = numberProblem(text, range, kind, range_text);
        // As digits, which CLI11 converts to an integer ("1e3" -> "1000").
        if (problem.empty() && kind != NumberKind::Real)
          text = std::to_string(parseNumber(text, range, kind).whole);
        return problem;
      },
      range_text);
}

// [min, max] and (min, max]; whole numbers in [min, max].
inline CLI::Validator realIn(double min, double max, const std::string& unit = "") {
  return numberIn({min, max, false, false, ""}, NumberKind::Real, unit);
}
inline CLI::Validator positiveUpTo(double max, const std::string& unit = "") {
  return numberIn({0.0, max, true, false, ""}, NumberKind::Real, unit);
}
inline CLI::Validator countIn(double min, double max) {
  return numberIn({min, max, false, false, ""}, NumberKind::Count);
}

// A random seed: any 64-bit unsigned number (CLI11 would wrap -5 around).
inline CLI::Validator seedNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t seed = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seed);
        if (error == std::errc() && end == text.data() + text.size() && !text.empty()) return "";
        return "must be a whole number in [0, 18446744073709551615], got " + text +
               (error == std::errc::result_out_of_range ? " (too large)" : "");
      },
      "SEED");
}

// A map's voxel: 0 keeps every point; else as the settings' downsampling
// voxels, [1 mm, 100 m] (below, points are never merged; above, a map of
// a few points).
inline CLI::Validator mapVoxel() {
  return numberIn({1e-3, 100.0, false, false, "keep every point"}, NumberKind::Real, "m");
}

}  // namespace hba::cli
