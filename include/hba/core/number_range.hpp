#pragma once
// The numbers a value takes (a setting, a flag) and the reading of one from
// text, with one wording for every message: "must be [0.01, 100], got 500
// (too large)". Non-finite text ("inf", "nan") is never a value.
#include <limits>
#include <string>

namespace hba {

// Between min and max (either end open, either end unbounded), and 0 too
// when `zero` names what 0 means ("off", "automatic").
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;
  std::string zero;
};

enum class NumberKind {
  Real,     // double
  Integer,  // int
  Count,    // a std::size_t, up to long long's range
};

// The shortest text that reads back the same: 0.1, 2147483647, inf.
std::string numberText(double value);
// ">= 2", "[0.01, 100]", "0 (off) or (0, 1)".
std::string rangeText(const NumberRange& range);
// `value` lies in the range (or is 0 when 0 means something).
bool inRange(const NumberRange& range, double value);

struct ParsedNumber {
  double value = 0.0;   // Real
  long long whole = 0;  // Integer and Count (exact beyond 2^53)
  std::string why;      // "" when read and in range
  bool ok = false;
};
// Reads `text` ("2", "+0.5", "1e3"; a whole number for Integer and Count).
// When not ok, `why` says why: "not a number", "not finite", "not a whole
// number", "too large", "too small", or "outside" (out of the range).
ParsedNumber parseNumber(const std::string& text, const NumberRange& range, NumberKind kind);

// "" if `text` is a number in the range, else "must be RANGE, got TEXT (why)";
// `range_text` stands for rangeText(range) (with a unit, a relation).
std::string numberProblem(const std::string& text, const NumberRange& range, NumberKind kind,
                          const std::string& range_text);

}  // namespace hba
