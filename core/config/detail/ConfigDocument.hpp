#pragma once
/// PRIVATE to core/config/*.cpp: the parsed TOML document behind every ConfigTable view. This
/// header includes toml++, which is a private dependency of regolith::core; no public header
/// may include it.
#include <toml++/toml.h>

#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace regolith::core::detail {

/// One table of the document that somebody opened as a ConfigTable: where it is, what it is
/// called, and which keys the program asked for (present or not). A key that is present but
/// never asked for is unknown (`ConfigTable::rejectUnknownKeys`).
struct TableEntry {
    toml::table* table = nullptr;
    std::string path; ///< dotted path from the root, "" for the root itself
    std::set<std::string, std::less<>> requested;
};

/// The TOML root table plus the registry of opened tables. Views hold it by shared_ptr, so a
/// sub-table view stays valid when the view of its parent is gone.
class ConfigDocument {
public:
    ConfigDocument(toml::table root, std::string sourceName);

    [[nodiscard]] toml::table& root() { return m_root; }
    [[nodiscard]] std::string const& sourceName() const { return m_sourceName; }

    /// The registry index of `table` (registered under `path` on first sight).
    std::size_t entryFor(toml::table& table, std::string path);
    [[nodiscard]] TableEntry& entry(std::size_t id) { return m_entries[id]; }
    /// The registry entry of `table`, or nullptr if nobody ever opened it.
    [[nodiscard]] TableEntry const* findEntry(toml::table const& table) const;

    /// Remembers that nodes whose source path is `origin` came from a command-line override,
    /// so their location is printed as the override itself rather than as "file:line".
    void addOverrideOrigin(std::string origin) { m_overrideOrigins.insert(std::move(origin)); }

    /// Where `node` was defined: "file:line", the override ("--set a.b=1"), or, for a node
    /// without source information (a table created by an override), the location of its
    /// first located child; `fallback` if none is found.
    [[nodiscard]] std::string locate(toml::node const& node, std::string_view fallback) const;
    /// Where `node` itself was defined ("file:line" or the override), else `fallback`.
    [[nodiscard]] std::string locateOwn(toml::node const& node, std::string_view fallback) const;
    /// Where `key` (a key of some table) was written; same conventions as `locate`.
    [[nodiscard]] std::string locateKey(toml::key const& key, toml::node const& value,
                                        std::string_view fallback) const;
    /// The line of `node` in the scene file, 0 if it has none or came from an override.
    [[nodiscard]] std::size_t lineOf(toml::node const& node) const;

private:
    [[nodiscard]] std::string formatSource(toml::source_region const& src) const;

    toml::table m_root;
    std::string m_sourceName;
    std::vector<TableEntry> m_entries;
    std::unordered_map<toml::table const*, std::size_t> m_index;
    std::set<std::string, std::less<>> m_overrideOrigins;
};

/// The value written as the user would write it, compact and on one line:
/// `[4, 0, 4]`, `"sos"`, `{ min = [0, 0, 0], max = [1, 1, 1] }`; long values are shortened
/// with "...".
[[nodiscard]] std::string describeValue(toml::node const& node);

/// "a string", "an integer", "an array", ... for messages like "got true (a boolean)".
[[nodiscard]] std::string_view typeName(toml::node const& node);

/// `parent.key`, or `key` when parent is the root; array elements are written `name[i]`.
[[nodiscard]] std::string joinPath(std::string_view parent, std::string_view key);

} // namespace regolith::core::detail
