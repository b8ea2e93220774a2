#include "core/config/detail/ConfigDocument.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace regolith::core::detail {

ConfigDocument::ConfigDocument(toml::table root, std::string sourceName)
    : m_root(std::move(root))
    , m_sourceName(std::move(sourceName)) {
    entryFor(m_root, "");
}

std::size_t ConfigDocument::entryFor(toml::table& table, std::string path) {
    if (auto it = m_index.find(&table); it != m_index.end())
        return it->second;
    m_entries.push_back(TableEntry{&table, std::move(path), {}});
    m_index.emplace(&table, m_entries.size() - 1);
    return m_entries.size() - 1;
}

TableEntry const* ConfigDocument::findEntry(toml::table const& table) const {
    auto it = m_index.find(&table);
    return it == m_index.end() ? nullptr : &m_entries[it->second];
}

std::string ConfigDocument::formatSource(toml::source_region const& src) const {
    if (src.path && m_overrideOrigins.contains(*src.path))
        return *src.path;
    if (src.begin.line == 0)
        return {};
    return fmt::format("{}:{}", src.path ? *src.path : m_sourceName, src.begin.line);
}

std::string ConfigDocument::locate(toml::node const& node, std::string_view fallback) const {
    if (auto s = formatSource(node.source()); !s.empty())
        return s;
    // A table created on the path of an override has no source of its own: report the
    // override that created it (its first located descendant).
    if (auto const* t = node.as_table())
        for (auto const& [k, v] : *t)
            if (auto s = locateKey(k, v, ""); !s.empty())
                return s;
    if (auto const* a = node.as_array())
        for (auto const& v : *a)
            if (auto s = locate(v, ""); !s.empty())
                return s;
    return std::string(fallback);
}

std::string ConfigDocument::locateOwn(toml::node const& node, std::string_view fallback) const {
    auto s = formatSource(node.source());
    return s.empty() ? std::string(fallback) : s;
}

std::string ConfigDocument::locateKey(toml::key const& key, toml::node const& value,
                                      std::string_view fallback) const {
    // The value's own origin wins for overrides: `--set domain.blocks=...` replaced the value
    // but the key keeps the file's position.
    if (auto const& vs = value.source(); vs.path && m_overrideOrigins.contains(*vs.path))
        return *vs.path;
    if (auto s = formatSource(key.source()); !s.empty())
        return s;
    return locate(value, fallback);
}

std::size_t ConfigDocument::lineOf(toml::node const& node) const {
    auto const& src = node.source();
    if (src.path && m_overrideOrigins.contains(*src.path))
        return 0;
    return src.begin.line;
}

namespace {

constexpr std::size_t kDescribeBudget = 60;

bool isBareKey(std::string_view key) {
    return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-';
    });
}

void appendQuoted(std::string& out, std::string_view s) {
    out += '"';
    for (char const c : s) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\t':
            out += "\\t";
            break;
        case '\r':
            out += "\\r";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
            else
                out += c;
        }
    }
    out += '"';
}

void appendKey(std::string& out, std::string_view key) {
    if (isBareKey(key))
        out += key;
    else
        appendQuoted(out, key);
}

void appendValue(std::string& out, toml::node const& node) {
    if (auto const* a = node.as_array()) {
        out += '[';
        bool first = true;
        for (auto const& v : *a) {
            if (!first)
                out += ", ";
            if (out.size() > kDescribeBudget) {
                out += "...";
                break;
            }
            first = false;
            appendValue(out, v);
        }
        out += ']';
    } else if (auto const* t = node.as_table()) {
        out += t->empty() ? "{" : "{ ";
        bool first = true;
        for (auto const& [k, v] : *t) {
            if (!first)
                out += ", ";
            if (out.size() > kDescribeBudget) {
                out += "...";
                break;
            }
            first = false;
            appendKey(out, k.str());
            out += " = ";
            appendValue(out, v);
        }
        out += t->empty() ? "}" : " }";
    } else if (auto const* s = node.as_string()) {
        appendQuoted(out, s->get());
    } else if (auto const* i = node.as_integer()) {
        out += fmt::format("{}", i->get());
    } else if (auto const* f = node.as_floating_point()) {
        double const x = f->get();
        if (std::isnan(x))
            out += "nan";
        else if (std::isinf(x))
            out += x > 0 ? "inf" : "-inf";
        else {
            std::string const text = fmt::format("{}", x);
            out += text;
            if (text.find_first_of(".e") == std::string::npos)
                out += ".0"; // a float as TOML writes it: 10.0 is not the integer 10
        }
    } else if (auto const* b = node.as_boolean()) {
        out += b->get() ? "true" : "false";
    } else {
        std::ostringstream os; // dates and times: toml++ prints them as TOML
        node.visit([&os](auto const& v) { os << v; });
        out += os.str();
    }
}

} // namespace

std::string describeValue(toml::node const& node) {
    std::string out;
    appendValue(out, node);
    return out;
}

std::string_view typeName(toml::node const& node) {
    switch (node.type()) {
    case toml::node_type::boolean:
        return "a boolean";
    case toml::node_type::integer:
        return "an integer";
    case toml::node_type::floating_point:
        return "a number";
    case toml::node_type::string:
        return "a string";
    case toml::node_type::array:
        return "an array";
    case toml::node_type::table:
        return "a table";
    case toml::node_type::date:
        return "a date";
    case toml::node_type::time:
        return "a time";
    case toml::node_type::date_time:
        return "a date-time";
    case toml::node_type::none:
        break;
    }
    return "nothing";
}

std::string joinPath(std::string_view parent, std::string_view key) {
    std::string out(parent);
    if (!out.empty())
        out += '.';
    appendKey(out, key);
    return out;
}

} // namespace regolith::core::detail
