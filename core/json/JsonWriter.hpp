#pragma once
/// A small streaming JSON writer (RFC 8259) for run summaries and benchmark results.
#include "core/math/Vec3.hpp"

#include <concepts>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace regolith::core {

/// Builds one JSON document: `w.beginObject().member("ranks", 4).key("timing_s")
/// .beginObject()...endObject().endObject(); w.str()`. Numbers keep full precision (the
/// shortest decimal that reads back as the same double); NaN and infinities, which JSON
/// cannot express, are written as null. Strings are escaped; invalid UTF-8 bytes become
/// U+FFFD, so the output is always valid JSON. Misuse (a value without a key inside an
/// object, unbalanced end*, reading an unfinished document) throws core::Error. Not
/// collective.
class JsonWriter {
public:
    /// `indent` spaces per nesting level; 0 writes everything on one line.
    explicit JsonWriter(int indent = 2);

    JsonWriter& beginObject();
    JsonWriter& endObject();
    /// Arrays are written on one line when `inlined` (short arrays of numbers), else one
    /// element per line.
    JsonWriter& beginArray(bool inlined = false);
    JsonWriter& endArray();
    /// The key of the next value; only directly inside an object.
    JsonWriter& key(std::string_view name);

    JsonWriter& value(std::string_view s);
    JsonWriter& value(char const* s) { return value(std::string_view(s)); }
    JsonWriter& value(bool b);
    JsonWriter& value(double x);
    template <std::integral T>
    requires(!std::same_as<T, bool>) JsonWriter& value(T x) {
        if constexpr (std::is_signed_v<T>)
            return integer(static_cast<std::int64_t>(x));
        else
            return unsignedInteger(static_cast<std::uint64_t>(x));
    }
    /// An inline array of 3 numbers.
    JsonWriter& value(Vec3 const& v);
    /// An inline array of numbers.
    JsonWriter& value(std::span<double const> xs);
    JsonWriter& null();

    /// `key(name)` then `value(v)`.
    template <class T>
    JsonWriter& member(std::string_view name, T const& v) {
        key(name);
        return value(v);
    }

    /// The finished document (with a final newline). Throws core::Error if incomplete.
    [[nodiscard]] std::string const& str() const;

    /// `s` as a JSON string literal, quotes included.
    [[nodiscard]] static std::string quote(std::string_view s);
    /// `x` as a JSON number ("null" if not finite), shortest round-trip form.
    [[nodiscard]] static std::string number(double x);

private:
    struct Level {
        bool isObject = false;
        bool inlined = false;
        bool empty = true;
        bool haveKey = false; ///< objects: a key was written, its value is due
    };
    JsonWriter& integer(std::int64_t x);
    JsonWriter& unsignedInteger(std::uint64_t x);
    /// Separator and indentation before a value; checks that a value may come here.
    void beforeValue();
    void newline(std::size_t depth);
    JsonWriter& raw(std::string_view text);
    void finish();

    std::string m_out;
    std::vector<Level> m_stack;
    int m_indent;
    bool m_done = false;
};

} // namespace regolith::core
