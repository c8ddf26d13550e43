#pragma once
// The intended name for a typo (a config key, a subcommand, a flag), to say "did you mean ...?".
#include <cstddef>
#include <string>
#include <vector>

namespace imucal {

// Levenshtein distance: insertions, deletions and substitutions of one character each.
std::size_t editDistance(const std::string& a, const std::string& b);

// The name nearest to `word`, if it is fewer than `limit` edits away (the first of equals); "" otherwise.
// A far "nearest" name would mislead more than it helps.
std::string closestName(const std::string& word, const std::vector<std::string>& names, std::size_t limit = 3);

}  // namespace imucal
