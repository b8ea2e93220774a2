// ConfigTable::rejectUnknownKeys: every key present in the document must have been asked for
// by the program; anything else is a typo or a key that has no effect, and is reported.
#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/config/Suggest.hpp"
#include "core/config/detail/ConfigDocument.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace regolith::core {

namespace {

struct Finding {
    std::size_t line; ///< sort key: file order; overrides (line 0) last
    std::string text;
};

constexpr std::size_t kMaxReported = 20;

std::string hint(std::string_view key, detail::TableEntry const* entry) {
    if (!entry || entry->requested.empty())
        return {};
    std::vector<std::string> const known(entry->requested.begin(), entry->requested.end());
    if (auto const m = closestMatch(key, known))
        return fmt::format(" \u2014 did you mean '{}'?", *m);
    return fmt::format(" (known keys here: {})", fmt::join(known, ", "));
}

void collect(detail::ConfigDocument const& doc, toml::table const& table, std::string const& path,
             std::string const& tableLocation, std::vector<Finding>& out) {
    detail::TableEntry const* entry = doc.findEntry(table);
    for (auto const& [key, value] : table) {
        std::string const keyPath = detail::joinPath(path, key.str());
        std::string const where = doc.locateKey(key, value, tableLocation);
        if (!entry || !entry->requested.contains(key.str())) {
            std::size_t const line =
                doc.lineOf(value) > 0 ? doc.lineOf(value) : key.source().begin.line;
            out.push_back(
                {line == 0 ? std::numeric_limits<std::size_t>::max() : line,
                 fmt::format("{}: unknown key '{}'{}", where, keyPath, hint(key.str(), entry))});
            continue;
        }
        if (auto const* sub = value.as_table()) {
            collect(doc, *sub, keyPath, where, out);
        } else if (auto const* array = value.as_array()) {
            std::size_t i = 0;
            for (auto const& element : *array) {
                if (auto const* t = element.as_table())
                    collect(doc, *t, fmt::format("{}[{}]", keyPath, i), doc.locate(*t, where), out);
                ++i;
            }
        }
    }
}

} // namespace

void ConfigTable::rejectUnknownKeys() const {
    std::vector<Finding> findings;
    collect(*m_doc, *m_doc->entry(m_id).table, path(), location(), findings);
    if (findings.empty())
        return;
    std::stable_sort(findings.begin(), findings.end(),
                     [](Finding const& a, Finding const& b) { return a.line < b.line; });
    std::string message;
    for (std::size_t i = 0; i < findings.size() && i < kMaxReported; ++i)
        message += (i == 0 ? "" : "\n") + findings[i].text;
    if (findings.size() > kMaxReported)
        message += fmt::format("\n... and {} more unknown keys", findings.size() - kMaxReported);
    throw InputError(message);
}

} // namespace regolith::core
