#include "pose_file_lines.hpp"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

[[noreturn]] void failAtLine(const fs::path& path, std::size_t line, const std::string& problem) {
  failAt(path, "line " + std::to_string(line) + ": " + problem);
}

double parseNumber(const fs::path& path, std::size_t line, std::string_view token, std::size_t column) {
  std::string_view digits = token;
  // from_chars rejects a leading '+', which some writers emit.
  if (digits.size() > 1 && digits.front() == '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range) {
    failAtLine(path, line,
               "number " + std::to_string(column) + " ('" + std::string(token) +
                   "') is out of the range of a double");
  }
  if (ec != std::errc() || end != digits.data() + digits.size()) {
    failAtLine(path, line, "'" + std::string(token) + "' is not a number");
  }
  if (!std::isfinite(value)) {
    failAtLine(path, line,
               "number " + std::to_string(column) + " is " + (std::isnan(value) ? "NaN" : "infinite") +
                   " ('" + std::string(token) + "')");
  }
  return value;
}

std::vector<double> parseRow(const fs::path& path, std::size_t line, std::string_view text) {
  std::vector<double> values;
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && isSpace(text[pos])) ++pos;
    std::size_t end = pos;
    while (end < text.size() && !isSpace(text[end])) ++end;
    if (end > pos) values.push_back(parseNumber(path, line, text.substr(pos, end - pos), values.size() + 1));
    pos = end;
  }
  return values;
}

// Calls on_row(row) for each data line; returns early when it returns false.
template <typename OnRow>
void forEachNumberRow(const fs::path& path, OnRow on_row) {
  const std::string content = readTextFile(path);  // checked a regular file, BOM dropped
  std::string_view rest(content);
  std::size_t line = 0;
  std::size_t pending_blank = 0;  // line number of a blank line not yet followed by data
  bool any_data = false;
  while (!rest.empty()) {
    ++line;
    const std::size_t newline = rest.find('\n');
    const std::string_view raw = rest.substr(0, newline);
    rest.remove_prefix(newline == std::string_view::npos ? rest.size() : newline + 1);
    const std::string_view text = trim(raw);
    if (!text.empty() && text.front() == '#') continue;
    if (text.empty()) {
      if (pending_blank == 0) pending_blank = line;
      continue;
    }
    if (pending_blank != 0 && any_data) {
      failAtLine(path, pending_blank, "blank line between poses (only blank lines at the end are allowed)");
    }
    pending_blank = 0;
    any_data = true;
    if (!on_row(NumberRow{line, parseRow(path, line, text)})) return;
  }
  if (!any_data) failAt(path, "empty file (no data lines)");
}

}  // namespace

std::vector<NumberRow> readNumberRows(const fs::path& path) {
  std::vector<NumberRow> rows;
  forEachNumberRow(path, [&](NumberRow row) {
    rows.push_back(std::move(row));
    return true;
  });
  return rows;
}

NumberRow readFirstNumberRow(const fs::path& path) {
  NumberRow first;
  forEachNumberRow(path, [&](NumberRow row) {
    first = std::move(row);
    return false;
  });
  return first;
}

}  // namespace hba::io::detail
