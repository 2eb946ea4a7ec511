#pragma once
// Locale-independent number parsing and word splitting for the text formats
// (PCD headers and ascii bodies, PLY headers and ascii bodies).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hba::io::detail {

// Whole-token parses: nullopt unless the entire token is one valid number.
// Floats accept "nan", "inf" and a leading '+', as writers in the wild emit them.
std::optional<float> parseFloat(std::string_view token);
std::optional<double> parseDouble(std::string_view token);
std::optional<std::uint64_t> parseUnsigned(std::string_view token);

// Returns the next word of `text` (split on spaces, tabs and '\r') and removes
// it and the blanks before it from `text`; empty when no word is left.
std::string_view nextWord(std::string_view& text);

// Like nextWord, but newlines separate words too (PLY ascii bodies are a
// stream of words; line breaks carry no meaning).
std::string_view nextToken(std::string_view& text);

// Returns the next line of `text` without its "\n" or "\r\n" and removes it
// from `text`.
std::string_view nextLine(std::string_view& text);

bool equalsIgnoreCase(std::string_view a, std::string_view b);

// For error messages: the token quoted and cut short if long or binary.
std::string quoteToken(std::string_view token);

}  // namespace hba::io::detail
