#pragma once
// The allowed name nearest to a misspelt one, for "did you mean" in messages.
#include <string>
#include <vector>

namespace shadelab
{
/// The number of single-character insertions, deletions, substitutions and swaps of two
/// neighbours that turn a into b (the optimal string alignment distance; F. J. Damerau, "A
/// technique for computer detection and correction of spelling errors", CACM 7(3), 1964).
std::size_t editDistance(const std::string& a, const std::string& b);

/// The name in `names` nearest to `word` by editDistance, if it is near enough to be what was
/// meant (at most a third of the word's letters changed, and at least one); "" otherwise, or
/// where two names are equally near.
std::string nearestName(const std::string& word, const std::vector<std::string>& names);
}
