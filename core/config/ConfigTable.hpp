#pragma once
/// Typed, typo-checking access to a TOML configuration (scene files). Knows nothing of blocks
/// or particles: each module parses its own section into plain structs with these getters.
///
/// Every error is a core::InputError whose message names where the value came from and its
/// full dotted key ("scene.toml:3: domain.blocks: expected an array of 3 positive integers,
/// got [4, 0, 4]"; values set on the command line are reported as "--set domain.blocks=..."
/// instead of "file:line"). Every rank reads the same input, so every rank throws the same
/// error. Keys the program asked for are recorded, so that `rejectUnknownKeys()` can report
/// any key that was never asked for, with a did-you-mean suggestion: a typo is never ignored.
///
/// None of these functions is collective; toml++ stays private to regolith::core.
#include "core/math/Vec3.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace regolith::core {

namespace detail {
class ConfigDocument;
template <class T>
struct IsStdArray : std::false_type {};
template <class T, std::size_t N>
struct IsStdArray<std::array<T, N>> : std::true_type {};
template <class T>
struct IsStdVector : std::false_type {};
template <class T>
struct IsStdVector<std::vector<T>> : std::true_type {};
} // namespace detail

/// What a key holds, for keys that accept more than one form (e.g. `velocity = [0, 1, 0]` or
/// `velocity = { random = [-1, 1], seed = 3 }`).
enum class ConfigKind { Missing, Boolean, Integer, Float, String, Array, Table, Other };

/// A view of one table of a parsed TOML document. Cheap to copy; views share the document.
/// Scalar types T for the getters: bool, int, std::int64_t, double (an integer is accepted as
/// a number), std::string and Vec3 (an array of 3 numbers); plus std::array<T, N> and
/// std::vector<T> of those.
class ConfigTable {
public:
    /// Sentinel for `getVector`: any number of elements.
    static constexpr std::size_t kAnySize = static_cast<std::size_t>(-1);

    /// Parses the file at `path`. Throws InputError naming the file when it cannot be read,
    /// or naming file, line, column and the parser's description when it is not valid TOML.
    [[nodiscard]] static ConfigTable fromFile(std::string const& path);
    /// Parses `text`; `name` stands for the file name in messages.
    [[nodiscard]] static ConfigTable fromString(std::string_view text, std::string name);

    /// Dotted path of this table from the root ("" for the root, "particles[1].region").
    [[nodiscard]] std::string const& path() const;
    /// Dotted path of `key` in this table ("domain.blocks").
    [[nodiscard]] std::string keyPath(std::string_view key) const;
    /// The file name (or the name given to fromString) of the document.
    [[nodiscard]] std::string const& sourceName() const;

    /// Is `key` present? Marks `key` as known (it is no typo even if present and unread).
    [[nodiscard]] bool has(std::string_view key) const;
    /// What `key` holds (ConfigKind::Missing if absent). Marks `key` as known.
    [[nodiscard]] ConfigKind kindOf(std::string_view key) const;

    /// The value of a required key. Throws InputError if it is missing (suggesting a present
    /// key that looks like a misspelling of it) or has the wrong type.
    template <class T>
    [[nodiscard]] T get(std::string_view key) const {
        if constexpr (detail::IsStdArray<T>::value) {
            auto v = getVector<typename T::value_type>(key, std::tuple_size_v<T>);
            T out{};
            std::copy(v.begin(), v.end(), out.begin());
            return out;
        } else if constexpr (detail::IsStdVector<T>::value) {
            return getVector<typename T::value_type>(key);
        } else {
            return getScalar<T>(key);
        }
    }
    /// The value of an optional key, `fallback` when absent; wrong types still throw.
    template <class T>
    [[nodiscard]] T getOr(std::string_view key, T fallback) const {
        return has(key) ? get<T>(key) : std::move(fallback);
    }
    /// `get<T>(key)`, then fails with "expected <what>, got <value>" unless `ok(value)`.
    template <class T, class Pred>
    [[nodiscard]] T getIf(std::string_view key, Pred&& ok, std::string_view what) const {
        T value = get<T>(key);
        if (!ok(value))
            failExpected(key, what);
        return value;
    }
    /// As `getIf` for an optional key; `fallback` (not checked) when absent.
    template <class T, class Pred>
    [[nodiscard]] T getOrIf(std::string_view key, T fallback, Pred&& ok,
                            std::string_view what) const {
        return has(key) ? getIf<T>(key, std::forward<Pred>(ok), what) : std::move(fallback);
    }

    /// An array of T with `size` elements (any length with kAnySize).
    template <class T>
    [[nodiscard]] std::vector<T> getVector(std::string_view key, std::size_t size = kAnySize) const;
    template <class T, std::size_t N>
    [[nodiscard]] std::array<T, N> getArray(std::string_view key) const {
        return get<std::array<T, N>>(key);
    }
    [[nodiscard]] std::string getString(std::string_view key) const {
        return get<std::string>(key);
    }
    [[nodiscard]] bool getBool(std::string_view key) const { return get<bool>(key); }
    [[nodiscard]] Vec3 getVec3(std::string_view key) const { return get<Vec3>(key); }

    /// A string that must be one of `choices`; returns its index. The error lists the
    /// choices and suggests the closest ("expected one of "nns", "sos", "hybrid", got "sso"
    /// — did you mean "sos"?").
    [[nodiscard]] std::size_t getChoice(std::string_view key,
                                        std::span<std::string_view const> choices) const;
    /// As getChoice for an optional key; `fallback` when absent.
    [[nodiscard]] std::size_t getChoiceOr(std::string_view key,
                                          std::span<std::string_view const> choices,
                                          std::size_t fallback) const {
        return has(key) ? getChoice(key, choices) : fallback;
    }

    /// A required sub-table (a `[section]` or an inline `{ ... }` table).
    [[nodiscard]] ConfigTable table(std::string_view key) const;
    /// An optional sub-table: nullopt when absent, InputError when not a table.
    [[nodiscard]] std::optional<ConfigTable> findTable(std::string_view key) const;
    /// An optional array of tables (`[[particles]]` or `refine = [{...}, {...}]`): empty
    /// when absent, InputError when not an array of tables.
    [[nodiscard]] std::vector<ConfigTable> tableArray(std::string_view key) const;

    /// Where `key` was written ("scene.toml:7", "--set time.dt=1"), or where this table was
    /// if `key` is absent.
    [[nodiscard]] std::string location(std::string_view key) const;
    /// Where this table was defined ("scene.toml:4"; the file name for the root).
    [[nodiscard]] std::string location() const;
    /// Does `key` hold the same value here and in `other` (tables and arrays compared in full,
    /// both absent counting as the same)?
    [[nodiscard]] bool sameValue(std::string_view key, ConfigTable const& other) const;
    /// The value of `key` as written, compact: `[4, 0, 4]`, `"sos"`; "(missing)" if absent.
    [[nodiscard]] std::string describe(std::string_view key) const;

    /// Throws InputError "<location>: <path.key>: <message>".
    [[noreturn]] void fail(std::string_view key, std::string_view message) const;
    /// Throws InputError "<location>: <path.key>: expected <what>, got <value as written>".
    [[noreturn]] void failExpected(std::string_view key, std::string_view what) const;

    /// Throws InputError listing every key of this table and its sub-tables (recursively)
    /// that nobody asked for, one per line in file order, each with its location and a
    /// did-you-mean suggestion among the keys asked for in the same table. Call it after
    /// every section has been parsed.
    void rejectUnknownKeys() const;

    /// Applies "a.b.c=value" to this table (normally the root), before anything is read.
    /// The value is TOML (`1e-3`, `true`, `"sos"`, `[2, 2, 2]`, `{ min = [0, 0, 0] }`); a
    /// bare word that is not valid TOML is taken as a string (`sos`). Path segments that are
    /// integers index arrays of tables: "particles.0.radius" or "particles[0].radius".
    /// Missing tables on the path are created (an unknown key then shows up in
    /// rejectUnknownKeys). Values keep `origin` (default "--set <assignment>") as their
    /// location in later messages. Throws InputError for a malformed assignment or value.
    void applyOverride(std::string_view assignment, std::string_view origin = {});

private:
    ConfigTable(std::shared_ptr<detail::ConfigDocument> doc, std::size_t id);
    template <class T>
    [[nodiscard]] T getScalar(std::string_view key) const;

    std::shared_ptr<detail::ConfigDocument> m_doc;
    std::size_t m_id = 0;
};

} // namespace regolith::core
