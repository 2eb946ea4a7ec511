#include "text_parsing.hpp"

#include <charconv>
#include <string>

namespace hba::io::detail {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
bool isSpace(char c) { return isBlank(c) || c == '\n' || c == '\v' || c == '\f'; }

template <typename IsSeparator>
std::string_view takeWord(std::string_view& text, IsSeparator is_separator) {
  std::size_t begin = 0;
  while (begin < text.size() && is_separator(text[begin])) ++begin;
  std::size_t end = begin;
  while (end < text.size() && !is_separator(text[end])) ++end;
  const std::string_view word = text.substr(begin, end - begin);
  text.remove_prefix(end);
  return word;
}

template <typename T>
std::optional<T> parseWhole(std::string_view token) {
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);  // from_chars rejects '+', but "+1.5" is a valid number
    if (!token.empty() && token.front() == '-') return std::nullopt;
  }
  T value{};
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

}  // namespace

std::optional<float> parseFloat(std::string_view token) { return parseWhole<float>(token); }
std::optional<double> parseDouble(std::string_view token) { return parseWhole<double>(token); }
std::optional<std::uint64_t> parseUnsigned(std::string_view token) {
  return parseWhole<std::uint64_t>(token);
}

std::string_view nextWord(std::string_view& text) { return takeWord(text, isBlank); }
std::string_view nextToken(std::string_view& text) { return takeWord(text, isSpace); }

std::string_view nextLine(std::string_view& text) {
  const std::size_t newline = text.find('\n');
  std::string_view line = text.substr(0, newline);
  text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

std::string quoteToken(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown;
  for (const char c : token.substr(0, kMaxShown)) {
    shown += (c >= 32 && c < 127) ? c : '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return "'" + shown + "'";
}

}  // namespace hba::io::detail
