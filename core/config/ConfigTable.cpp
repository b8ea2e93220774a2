#include "core/config/ConfigTable.hpp"

#include "core/Error.hpp"
#include "core/config/ConfigFile.hpp"
#include "core/config/Suggest.hpp"
#include "core/config/detail/ConfigDocument.hpp"

#include <fmt/format.h>

#include <limits>
#include <type_traits>

namespace regolith::core {

using detail::ConfigDocument;

namespace {

/// Converts a TOML node to T, nullopt if it does not hold a T.
template <class T>
std::optional<T> convert(toml::node const& n) {
    if constexpr (std::is_same_v<T, bool>) {
        return n.value_exact<bool>();
    } else if constexpr (std::is_same_v<T, std::int64_t>) {
        return n.value_exact<std::int64_t>();
    } else if constexpr (std::is_same_v<T, int>) {
        auto const v = n.value_exact<std::int64_t>();
        if (v && *v >= std::numeric_limits<int>::min() && *v <= std::numeric_limits<int>::max())
            return static_cast<int>(*v);
        return std::nullopt;
    } else if constexpr (std::is_same_v<T, double>) {
        if (auto const* f = n.as_floating_point())
            return f->get();
        if (auto const* i = n.as_integer())
            return static_cast<double>(i->get());
        return std::nullopt;
    } else if constexpr (std::is_same_v<T, std::string>) {
        return n.value_exact<std::string>();
    } else if constexpr (std::is_same_v<T, Vec3>) {
        auto const* a = n.as_array();
        if (!a || a->size() != 3)
            return std::nullopt;
        Vec3 out;
        Eigen::Index d = 0;
        for (auto const& element : *a) {
            auto const x = convert<double>(element);
            if (!x)
                return std::nullopt;
            out[d++] = *x;
        }
        return out;
    } else {
        static_assert(sizeof(T) == 0, "unsupported configuration value type");
    }
}

template <class T>
constexpr std::string_view singular() {
    if constexpr (std::is_same_v<T, bool>)
        return "a boolean";
    else if constexpr (std::is_same_v<T, int>)
        return "an integer (32 bit)";
    else if constexpr (std::is_same_v<T, std::int64_t>)
        return "an integer";
    else if constexpr (std::is_same_v<T, double>)
        return "a number";
    else if constexpr (std::is_same_v<T, std::string>)
        return "a string";
    else
        return "an array of 3 numbers";
}

template <class T>
constexpr std::string_view plural() {
    if constexpr (std::is_same_v<T, bool>)
        return "booleans";
    else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, std::int64_t>)
        return "integers";
    else if constexpr (std::is_same_v<T, double>)
        return "numbers";
    else if constexpr (std::is_same_v<T, std::string>)
        return "strings";
    else
        return "arrays of 3 numbers";
}

} // namespace

ConfigTable::ConfigTable(std::shared_ptr<ConfigDocument> doc, std::size_t id)
    : m_doc(std::move(doc))
    , m_id(id) {}

ConfigTable ConfigTable::fromString(std::string_view text, std::string name) {
    toml::table root;
    try {
        root = toml::parse(text, std::string_view(name));
    } catch (toml::parse_error const& e) {
        throw InputError(fmt::format("{}:{}:{}: malformed TOML: {}", name, e.source().begin.line,
                                     e.source().begin.column, e.description()));
    }
    auto doc = std::make_shared<ConfigDocument>(std::move(root), std::move(name));
    return {std::move(doc), 0};
}

ConfigTable ConfigTable::fromFile(std::string const& path) {
    return fromString(readTextFile(path), path);
}

std::string const& ConfigTable::path() const {
    return m_doc->entry(m_id).path;
}

std::string ConfigTable::keyPath(std::string_view key) const {
    return detail::joinPath(path(), key);
}

std::string const& ConfigTable::sourceName() const {
    return m_doc->sourceName();
}

bool ConfigTable::has(std::string_view key) const {
    auto& e = m_doc->entry(m_id);
    e.requested.emplace(key);
    return e.table->contains(key);
}

ConfigKind ConfigTable::kindOf(std::string_view key) const {
    if (!has(key))
        return ConfigKind::Missing;
    switch (m_doc->entry(m_id).table->get(key)->type()) {
    case toml::node_type::boolean:
        return ConfigKind::Boolean;
    case toml::node_type::integer:
        return ConfigKind::Integer;
    case toml::node_type::floating_point:
        return ConfigKind::Float;
    case toml::node_type::string:
        return ConfigKind::String;
    case toml::node_type::array:
        return ConfigKind::Array;
    case toml::node_type::table:
        return ConfigKind::Table;
    default:
        return ConfigKind::Other;
    }
}

namespace {

/// The node of a required key, or an InputError that points at a present, unasked-for key
/// that looks like a misspelling of it.
toml::node& requireNode(ConfigTable const& view, ConfigDocument& doc, std::size_t id,
                        std::string_view key) {
    auto& e = doc.entry(id);
    e.requested.emplace(key);
    if (auto* n = e.table->get(key))
        return *n;
    std::vector<std::string> unasked;
    for (auto const& [k, v] : *e.table)
        if (!e.requested.contains(k.str()))
            unasked.emplace_back(k.str());
    std::string hint;
    if (auto const m = closestMatch(key, unasked))
        hint = fmt::format(" (is '{}' at {} a misspelling of it?)", *m, view.location(*m));
    throw InputError(
        fmt::format("{}: {}: required key is missing{}", view.location(), view.keyPath(key), hint));
}

[[noreturn]] void failType(ConfigTable const& view, toml::node const& n, std::string_view key,
                           std::string_view what) {
    if (n.is_array() || n.is_table())
        view.failExpected(key, what);
    view.fail(key, fmt::format("expected {}, got {} ({})", what, detail::describeValue(n),
                               detail::typeName(n)));
}

} // namespace

template <class T>
T ConfigTable::getScalar(std::string_view key) const {
    toml::node const& n = requireNode(*this, *m_doc, m_id, key);
    if (auto v = convert<T>(n))
        return *v;
    failType(*this, n, key, singular<T>());
}

template <class T>
std::vector<T> ConfigTable::getVector(std::string_view key, std::size_t size) const {
    toml::node const& n = requireNode(*this, *m_doc, m_id, key);
    std::string const what = size == kAnySize ? fmt::format("an array of {}", plural<T>())
                                              : fmt::format("an array of {} {}", size, plural<T>());
    auto const* a = n.as_array();
    if (!a || (size != kAnySize && a->size() != size))
        failType(*this, n, key, what);
    std::vector<T> out;
    out.reserve(a->size());
    for (auto const& element : *a) {
        auto v = convert<T>(element);
        if (!v)
            failType(*this, n, key, what);
        out.push_back(std::move(*v));
    }
    return out;
}

#define REGOLITH_CONFIG_INSTANTIATE(T)                                                             \
    template T ConfigTable::getScalar<T>(std::string_view) const;                                  \
    template std::vector<T> ConfigTable::getVector<T>(std::string_view, std::size_t) const;
REGOLITH_CONFIG_INSTANTIATE(bool)
REGOLITH_CONFIG_INSTANTIATE(int)
REGOLITH_CONFIG_INSTANTIATE(std::int64_t)
REGOLITH_CONFIG_INSTANTIATE(double)
REGOLITH_CONFIG_INSTANTIATE(std::string)
REGOLITH_CONFIG_INSTANTIATE(Vec3)
#undef REGOLITH_CONFIG_INSTANTIATE

std::size_t ConfigTable::getChoice(std::string_view key,
                                   std::span<std::string_view const> choices) const {
    std::string const value = getString(key);
    std::vector<std::string> names;
    for (auto const c : choices) {
        if (c == value)
            return names.size();
        names.emplace_back(c);
    }
    std::string quoted;
    for (auto const& n : names)
        quoted += (quoted.empty() ? "\"" : ", \"") + n + "\"";
    std::string hint;
    if (auto const m = closestMatch(value, names))
        hint = fmt::format(" \u2014 did you mean \"{}\"?", *m);
    fail(key, fmt::format("expected one of {}, got {}{}", quoted, describe(key), hint));
}

ConfigTable ConfigTable::table(std::string_view key) const {
    auto& e = m_doc->entry(m_id);
    e.requested.emplace(key);
    if (!e.table->contains(key))
        throw InputError(fmt::format("{}: missing required table [{}]", location(), keyPath(key)));
    return *findTable(key);
}

std::optional<ConfigTable> ConfigTable::findTable(std::string_view key) const {
    if (!has(key))
        return std::nullopt;
    toml::node& n = *m_doc->entry(m_id).table->get(key);
    auto* t = n.as_table();
    if (!t)
        failType(*this, n, key, "a table");
    std::size_t const id = m_doc->entryFor(*t, keyPath(key));
    return ConfigTable(m_doc, id);
}

std::vector<ConfigTable> ConfigTable::tableArray(std::string_view key) const {
    if (!has(key))
        return {};
    toml::node& n = *m_doc->entry(m_id).table->get(key);
    auto* a = n.as_array();
    if (!a || (!a->empty() && !a->is_array_of_tables()))
        failType(*this, n, key, fmt::format("an array of tables ([[{}]] sections)", key));
    std::vector<ConfigTable> out;
    std::size_t i = 0;
    for (auto& element : *a) {
        std::size_t const id =
            m_doc->entryFor(*element.as_table(), fmt::format("{}[{}]", keyPath(key), i++));
        out.push_back(ConfigTable(m_doc, id));
    }
    return out;
}

std::string ConfigTable::location() const {
    // Only the table's own position: a table created by `--set time.steps=3` is no more
    // "from --set" than from the file when its required `dt` is missing.
    if (m_id == 0)
        return sourceName();
    return m_doc->locateOwn(*m_doc->entry(m_id).table, sourceName());
}

std::string ConfigTable::location(std::string_view key) const {
    auto const& t = *m_doc->entry(m_id).table;
    if (auto it = t.find(key); it != t.end())
        return m_doc->locateKey(it->first, it->second, location());
    return location();
}

bool ConfigTable::sameValue(std::string_view key, ConfigTable const& other) const {
    auto const* a = m_doc->entry(m_id).table->get(key);
    auto const* b = other.m_doc->entry(other.m_id).table->get(key);
    if (a == nullptr || b == nullptr)
        return a == b;
    return a->visit([b](auto const& x) {
        return b->visit([&x](auto const& y) {
            if constexpr (std::is_same_v<decltype(x), decltype(y)>)
                return x == y; // toml++ compares tables and arrays element by element
            else
                return false;
        });
    });
}

std::string ConfigTable::describe(std::string_view key) const {
    if (auto const* n = m_doc->entry(m_id).table->get(key))
        return detail::describeValue(*n);
    return "(missing)";
}

void ConfigTable::fail(std::string_view key, std::string_view message) const {
    throw InputError(fmt::format("{}: {}: {}", location(key), keyPath(key), message));
}

void ConfigTable::failExpected(std::string_view key, std::string_view what) const {
    fail(key, fmt::format("expected {}, got {}", what, describe(key)));
}

} // namespace regolith::core
