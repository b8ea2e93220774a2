#include "core/config/Suggest.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

namespace regolith::core {

std::size_t editDistance(std::string_view a, std::string_view b) {
    std::size_t const n = a.size();
    std::size_t const m = b.size();
    // Three rows of the (n+1) x (m+1) table suffice: the transposition looks two rows back.
    std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
    for (std::size_t j = 0; j <= m; ++j)
        prev[j] = j;
    for (std::size_t i = 1; i <= n; ++i) {
        cur[0] = i;
        for (std::size_t j = 1; j <= m; ++j) {
            std::size_t const cost = a[i - 1] == b[j - 1] ? 0 : 1;
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                cur[j] = std::min(cur[j], prev2[j - 2] + 1);
        }
        std::swap(prev2, prev);
        std::swap(prev, cur);
    }
    return prev[m];
}

namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

} // namespace

std::optional<std::string> closestMatch(std::string_view word,
                                        std::span<std::string const> candidates) {
    std::string const w = lower(word);
    std::size_t const limit = std::max<std::size_t>(1, (word.size() + 1) / 3);
    std::optional<std::string> best;
    std::size_t bestDistance = limit + 1;
    for (auto const& c : candidates) {
        std::size_t const d = lower(c) == w ? 0 : editDistance(word, c);
        // Replacing every letter of the shorter word is no misspelling ("b" for "a").
        if (d >= std::max(word.size(), c.size()))
            continue;
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

} // namespace regolith::core
