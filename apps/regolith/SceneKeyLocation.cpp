#include "apps/regolith/SceneKeyLocation.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cstddef>
#include <optional>

namespace regolith::apps {

namespace {

/// "walls[3].normal: ..." -> ("walls", 3) and the rest after "]"; nullopt if not an entry key
/// of [[particles]], [[walls]] or [[insert]].
struct EntryRef {
    std::string_view array;
    std::size_t index = 0;
    std::string_view path; ///< after "]": "", ".spacing", ".velocity.random", ...
};

std::optional<EntryRef> parseEntryRef(std::string_view key) {
    for (std::string_view const array :
         std::array<std::string_view, 3>{"particles", "walls", "insert"}) {
        if (!key.starts_with(array) || key.size() <= array.size() || key[array.size()] != '[')
            continue;
        auto const digits = key.substr(array.size() + 1);
        EntryRef ref{array, 0, {}};
        auto const [end, ec] =
            std::from_chars(digits.data(), digits.data() + digits.size(), ref.index);
        if (ec != std::errc() || end == digits.data() || end == digits.data() + digits.size() ||
            *end != ']')
            return std::nullopt;
        ref.path = digits.substr(static_cast<std::size_t>(end - digits.data()) + 1);
        return ref;
    }
    return std::nullopt;
}

/// The location of the deepest existing key of `path` (".a.b[2].c") below `table`.
std::string locatePath(core::ConfigTable table, std::string_view path) {
    std::string where = table.location();
    while (path.starts_with('.')) {
        path.remove_prefix(1);
        auto const dot = path.find('.');
        std::string_view const segment = path.substr(0, dot);
        std::string_view const name = segment.substr(0, segment.find('['));
        path = dot == std::string_view::npos ? std::string_view{} : path.substr(dot);
        if (name.empty() || !table.has(name))
            break;
        where = table.location(name);
        if (path.empty() || table.kindOf(name) != core::ConfigKind::Table)
            break;
        table = table.table(name);
    }
    return where;
}

} // namespace

std::string locateSceneKey(core::ConfigTable const& root, std::string_view message) {
    auto const colon = message.find(": ");
    if (colon == std::string_view::npos)
        return std::string(message);
    auto const ref = parseEntryRef(message.substr(0, colon));
    if (!ref || ref->path.find_first_of(" \t'\"") != std::string_view::npos)
        return std::string(message);
    auto const entries = root.tableArray(ref->array);
    if (ref->index >= entries.size())
        return std::string(message);
    std::string where = locatePath(entries[ref->index], ref->path);
    return where + ": " + std::string(message);
}

std::string locateSectionKey(core::ConfigTable const& root, std::string_view message) {
    // "section.key" up to the first character that cannot be in a dotted key.
    std::size_t end = 0;
    while (end < message.size() && (std::isalnum(static_cast<unsigned char>(message[end])) != 0 ||
                                    message[end] == '_' || message[end] == '.'))
        ++end;
    std::string_view const key = message.substr(0, end);
    std::string_view const rest = message.substr(end);
    auto const dot = key.find('.');
    if (dot == std::string_view::npos || dot == 0 || dot + 1 == key.size() ||
        key.find('.', dot + 1) != std::string_view::npos ||
        !(rest.starts_with(" = ") || rest.starts_with(": ")))
        return std::string(message);
    auto const section = root.findTable(key.substr(0, dot));
    std::string_view const name = key.substr(dot + 1);
    if (!section || !section->has(name))
        return std::string(message);
    return section->location(name) + ": " + std::string(message);
}

} // namespace regolith::apps
