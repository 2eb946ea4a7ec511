#pragma once
// "Did you mean ...?" for mistyped commands, flags and setting names.
#include <optional>
#include <string>
#include <vector>

namespace hba {

// Edit distance (insertions, deletions, substitutions, swaps of neighbours).
std::size_t editDistance(const std::string& a, const std::string& b);

// The candidate closest to `word`, if it is close enough to be a typo of it
// (at most 2 edits, and fewer than a third of the word). Ties: the first.
std::optional<std::string> closestMatch(const std::string& word, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" or "".
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace hba
