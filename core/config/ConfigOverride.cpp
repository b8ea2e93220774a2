// ConfigTable::applyOverride: command-line `--set a.b.c=value` edits of a parsed document.
#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/config/detail/ConfigDocument.hpp"

#include <fmt/format.h>

#include <charconv>

namespace regolith::core {

namespace {

std::string_view trim(std::string_view s) {
    auto const first = s.find_first_not_of(" \t");
    if (first == std::string_view::npos)
        return {};
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

/// Splits "a.b[0].c" / "a.b.0.c" into {"a", "b", "0", "c"}; empty result if malformed.
std::vector<std::string> splitKeyPath(std::string_view path) {
    std::vector<std::string> out;
    std::string current;
    bool afterIndex = false; // just closed "[i]": only '.' or '[' may follow
    for (std::size_t i = 0; i < path.size(); ++i) {
        char const c = path[i];
        if (c == '.' || c == '[') {
            if (current.empty() && !afterIndex)
                return {};
            if (!current.empty())
                out.push_back(std::move(current));
            current.clear();
            afterIndex = false;
            if (c == '[') {
                auto const close = path.find(']', i);
                if (close == std::string_view::npos || close == i + 1)
                    return {};
                out.emplace_back(path.substr(i + 1, close - i - 1));
                i = close;
                afterIndex = true;
            }
        } else if (afterIndex) {
            return {};
        } else {
            current += c;
        }
    }
    if (current.empty() && !afterIndex)
        return {};
    if (!current.empty())
        out.push_back(std::move(current));
    for (auto const& s : out)
        for (char const c : s)
            if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '_' || c == '-'))
                return {};
    return out;
}

std::optional<std::size_t> parseIndex(std::string_view s) {
    std::size_t value = 0;
    auto const [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc{} || end != s.data() + s.size())
        return std::nullopt;
    return value;
}

/// The value of an override as a TOML node whose source path is `origin`. A bare word that is
/// not a number or boolean becomes a string, so `--set sync.method=sos` works without shell
/// quoting -- also one that TOML would read as a date or time (`--set output.dir=2024-05-01`:
/// no scene key takes a date).
toml::table parseValue(std::string_view value, std::string const& origin) {
    std::string const doc = fmt::format("v = {}", value);
    try {
        toml::table t = toml::parse(doc, std::string_view(origin));
        if (t.size() != 1 || !t.contains("v"))
            throw InputError(fmt::format("{}: the value must be a single TOML value", origin));
        toml::node const& v = *t.get("v");
        if (!(v.is_date() || v.is_time() || v.is_date_time()))
            return t;
    } catch (toml::parse_error const& e) {
        bool const bareWord = value.find_first_of("\"'[{\n\r#=") == std::string_view::npos;
        if (!bareWord)
            throw InputError(
                fmt::format("{}: malformed value '{}': {}", origin, value, e.description()));
    }
    // Re-parse the word as a TOML string so that the node keeps `origin` as its source.
    std::string escaped;
    for (char const c : value) {
        if (c == '\\')
            escaped += "\\\\";
        else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            escaped += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
        else
            escaped += c;
    }
    return toml::parse(fmt::format("v = \"{}\"", escaped), std::string_view(origin));
}

} // namespace

void ConfigTable::applyOverride(std::string_view assignment, std::string_view origin) {
    std::string const from =
        origin.empty() ? fmt::format("--set {}", assignment) : std::string(origin);
    auto const eq = assignment.find('=');
    std::string_view const keyText = trim(assignment.substr(0, eq));
    std::string_view const valueText =
        eq == std::string_view::npos ? std::string_view{} : trim(assignment.substr(eq + 1));
    auto const segments = splitKeyPath(keyText);
    if (eq == std::string_view::npos || segments.empty() || valueText.empty())
        throw InputError(
            fmt::format("{}: expected section.key=value (e.g. --set time.dt=1e-3)", from));

    toml::table parsed = parseValue(valueText, from);
    m_doc->addOverrideOrigin(from);

    // Walk to the container of the last segment, creating missing tables on the way.
    toml::node* current = m_doc->entry(m_id).table;
    toml::key const* key = nullptr; // of `current` in its table, if it is in one
    std::string walked = path();
    for (std::size_t i = 0; i < segments.size(); ++i) {
        std::string const& seg = segments[i];
        bool const last = i + 1 == segments.size();
        if (auto* table = current->as_table()) {
            if (last) {
                table->insert_or_assign(seg, std::move(*parsed.get("v")));
                return;
            }
            if (!table->contains(seg)) {
                // An index next names an entry of an array of tables the scene does not have;
                // the tables created here would only be refused later, as not an array.
                if (parseIndex(segments[i + 1]))
                    throw InputError(fmt::format(
                        "{}: the scene has no '{}' entries to take entry {} of (--set edits "
                        "the entries a scene file has; add a [[{}]] section to it)",
                        from, detail::joinPath(walked, seg), segments[i + 1], seg));
                table->insert(seg, toml::table{});
            }
            auto const it = table->find(seg);
            key = &it->first;
            current = &it->second;
            walked = detail::joinPath(walked, seg);
        } else if (auto* array = current->as_array()) {
            auto const index = parseIndex(seg);
            if (!index || *index >= array->size())
                throw InputError(fmt::format("{}: '{}' has {} entries; '{}' is not an index of it",
                                             from, walked, array->size(), seg));
            if (last) {
                array->replace(array->cbegin() + static_cast<std::ptrdiff_t>(*index),
                               std::move(*parsed.get("v")));
                return;
            }
            current = array->get(*index);
            walked = fmt::format("{}[{}]", walked, *index);
        } else {
            // Name where the blocking value was written: it may be another option's doing
            // (--set time=3 before --steps, which writes time.steps).
            std::string const where = key ? m_doc->locateKey(*key, *current, "") : "";
            throw InputError(fmt::format(
                "{}: '{}' is {}{}, not a table", from, walked, detail::typeName(*current),
                where.empty() || where == from ? "" : fmt::format(" (written by {})", where)));
        }
    }
}

} // namespace regolith::core
