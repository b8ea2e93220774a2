#pragma once
/// Did-you-mean suggestions for misspelt keys and option values.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace regolith::core {

/// Optimal-string-alignment distance between `a` and `b`: the number of insertions,
/// deletions, substitutions and transpositions of adjacent characters (each costs 1) that
/// turn one into the other, no substring edited twice (Damerau 1964, computed with the
/// Wagner–Fischer dynamic programme, 1974). "blokcs" -> "blocks" is 1. Case-sensitive.
[[nodiscard]] std::size_t editDistance(std::string_view a, std::string_view b);

/// The candidate closest to `word`, if it is close enough to be a plausible misspelling:
/// a case-insensitive match, or an edit distance of at most max(1, (|word| + 1) / 3)
/// (1 for "dtt", 2 for "blokcs") and below the length of the longer word (so "a" is not
/// offered for "b"); ties go to the first candidate in `candidates`.
[[nodiscard]] std::optional<std::string> closestMatch(std::string_view word,
                                                      std::span<std::string const> candidates);

} // namespace regolith::core
