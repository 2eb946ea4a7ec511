#include "hba/core/number_range.hpp"

#include <charconv>
#include <cmath>

namespace hba {

std::string numberText(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  // Whole numbers in digits: 1000000, not 1e+06.
  if (value == std::floor(value) && std::abs(value) < 1e15)
    return std::to_string(static_cast<long long>(value));
  char digits[32];
  return std::string(digits, std::to_chars(digits, digits + sizeof(digits), value).ptr);
}

std::string rangeText(const NumberRange& r) {
  const bool no_min = std::isinf(r.min);
  const bool no_max = std::isinf(r.max);
  std::string text;
  if (no_min && no_max) {
    text = "any number";
  } else if (no_max) {
    text = (r.min_open ? "> " : ">= ") + numberText(r.min);
  } else if (no_min) {
    text = (r.max_open ? "< " : "<= ") + numberText(r.max);
  } else {
    text = std::string(r.min_open ? "(" : "[") + numberText(r.min) + ", " + numberText(r.max) +
           (r.max_open ? ")" : "]");
  }
  return r.zero.empty() ? text : "0 (" + r.zero + ") or " + text;
}

bool inRange(const NumberRange& r, double v) {
  if (!std::isfinite(v)) return false;
  if (v == 0.0 && !r.zero.empty()) return true;
  const bool above = r.min_open ? v > r.min : v >= r.min;
  const bool below = r.max_open ? v < r.max : v <= r.max;
  return above && below;
}

ParsedNumber parseNumber(const std::string& text, const NumberRange& range, NumberKind kind) {
  ParsedNumber parsed;
  const auto refuse = [&](const std::string& why) {
    parsed.why = why;
    return parsed;
  };
  // from_chars reads no leading '+'.
  const std::string digits = !text.empty() && text.front() == '+' ? text.substr(1) : text;
  const char* first = digits.data();
  const char* last = first + digits.size();
  double number = 0.0;
  const auto [end, error] = std::from_chars(first, last, number);
  if (error == std::errc::result_out_of_range) {
    const auto exponent = digits.find_first_of("eE");
    const bool tiny = exponent != std::string::npos && digits.compare(exponent + 1, 1, "-") == 0;
    if (tiny) return refuse("too close to 0");
    return refuse(digits.front() == '-' ? "too small" : "too large");
  }
  if (digits.empty() || error != std::errc() || end != last) return refuse("not a number");
  if (!std::isfinite(number)) return refuse("not finite");
  parsed.value = number;
  if (kind != NumberKind::Real) {
    if (number != std::floor(number)) return refuse("not a whole number");
    // What the field holds: an int, or a count that travels as long long.
    const double most = kind == NumberKind::Integer ? std::numeric_limits<int>::max() : 9e18;
    const double least = kind == NumberKind::Integer ? std::numeric_limits<int>::min() : 0.0;
    if (number > most)
      return refuse(std::isinf(range.max) ? "too large: at most " + numberText(most) : "too large");
    if (number < least) return refuse("too small");
    parsed.whole = static_cast<long long>(number);
    long long exact = 0;  // digits beyond a double's 53 bits
    const auto whole = std::from_chars(first, last, exact);
    if (whole.ec == std::errc() && whole.ptr == last) parsed.whole = exact;
  }
  if (!inRange(range, number)) {
    const bool above = range.max_open ? number >= range.max : number > range.max;
    return refuse(above ? "too large" : "outside");
  }
  parsed.ok = true;
  return parsed;
}

std::string numberProblem(const std::string& text, const NumberRange& range, NumberKind kind,
                          const std::string& range_text) {
  const ParsedNumber parsed = parseNumber(text, range, kind);
  if (parsed.ok) return "";
  const bool plain = parsed.why == "outside";
  return "must be " + range_text + ", got " + text + (plain ? "" : " (" + parsed.why + ")");
}

}  // namespace hba
