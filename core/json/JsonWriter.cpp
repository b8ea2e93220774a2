#include "core/json/JsonWriter.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace regolith::core {

JsonWriter::JsonWriter(int indent)
    : m_indent(indent < 0 ? 0 : indent) {}

void JsonWriter::newline(std::size_t depth) {
    if (m_indent == 0)
        return;
    m_out += '\n';
    m_out.append(depth * static_cast<std::size_t>(m_indent), ' ');
}

void JsonWriter::beforeValue() {
    if (m_done)
        throw Error("JsonWriter: a second value after the finished document");
    if (m_stack.empty())
        return;
    Level& top = m_stack.back();
    if (top.isObject) {
        if (!top.haveKey)
            throw Error("JsonWriter: a value inside an object needs a key first");
        top.haveKey = false;
        return; // key() wrote the separator and indentation
    }
    if (!top.empty)
        m_out += top.inlined && m_indent > 0 ? ", " : ",";
    if (!top.inlined)
        newline(m_stack.size());
    top.empty = false;
}

void JsonWriter::finish() {
    m_done = true;
    m_out += '\n';
}

JsonWriter& JsonWriter::raw(std::string_view text) {
    beforeValue();
    m_out += text;
    if (m_stack.empty())
        finish();
    return *this;
}

JsonWriter& JsonWriter::beginObject() {
    beforeValue();
    m_out += '{';
    m_stack.push_back({true, false, true, false});
    return *this;
}

JsonWriter& JsonWriter::beginArray(bool inlined) {
    beforeValue();
    m_out += '[';
    m_stack.push_back({false, inlined || m_indent == 0, true, false});
    return *this;
}

JsonWriter& JsonWriter::endObject() {
    if (m_stack.empty() || !m_stack.back().isObject || m_stack.back().haveKey)
        throw Error("JsonWriter: endObject() without an open object (or after a bare key)");
    bool const empty = m_stack.back().empty;
    m_stack.pop_back();
    if (!empty)
        newline(m_stack.size());
    m_out += '}';
    if (m_stack.empty())
        finish();
    return *this;
}

JsonWriter& JsonWriter::endArray() {
    if (m_stack.empty() || m_stack.back().isObject)
        throw Error("JsonWriter: endArray() without an open array");
    Level const level = m_stack.back();
    m_stack.pop_back();
    if (!level.empty && !level.inlined)
        newline(m_stack.size());
    m_out += ']';
    if (m_stack.empty())
        finish();
    return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
    if (m_stack.empty() || !m_stack.back().isObject || m_stack.back().haveKey)
        throw Error(fmt::format("JsonWriter: key '{}' outside an object or twice in a row", name));
    Level& top = m_stack.back();
    if (!top.empty)
        m_out += ',';
    newline(m_stack.size());
    m_out += quote(name);
    m_out += m_indent == 0 ? ":" : ": ";
    top.empty = false;
    top.haveKey = true;
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view s) {
    return raw(quote(s));
}
JsonWriter& JsonWriter::value(bool b) {
    return raw(b ? "true" : "false");
}
JsonWriter& JsonWriter::value(double x) {
    return raw(number(x));
}
JsonWriter& JsonWriter::integer(std::int64_t x) {
    return raw(fmt::format("{}", x));
}
JsonWriter& JsonWriter::unsignedInteger(std::uint64_t x) {
    return raw(fmt::format("{}", x));
}
JsonWriter& JsonWriter::null() {
    return raw("null");
}

JsonWriter& JsonWriter::value(Vec3 const& v) {
    double const xs[3] = {v.x(), v.y(), v.z()};
    return value(std::span<double const>(xs));
}

JsonWriter& JsonWriter::value(std::span<double const> xs) {
    beginArray(true);
    for (double const x : xs)
        value(x);
    return endArray();
}

std::string const& JsonWriter::str() const {
    if (!m_done)
        throw Error("JsonWriter: the document is not finished");
    return m_out;
}

std::string JsonWriter::number(double x) {
    if (!std::isfinite(x))
        return "null";
    // fmt's default format is the shortest string that parses back to the same double
    // (Dragonbox); its forms ("0.1", "1e+20", "-0", "3") are all valid JSON numbers.
    return fmt::format("{}", x);
}

namespace {

/// Length of the well-formed UTF-8 sequence starting at s[i] (Unicode 15, Table 3-7), or 0.
std::size_t utf8Length(std::string_view s, std::size_t i) {
    auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    unsigned char const b0 = byte(i);
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF; // allowed range of the second byte
    if (b0 < 0x80)
        return 1;
    if (b0 >= 0xC2 && b0 <= 0xDF)
        n = 2;
    else if (b0 >= 0xE0 && b0 <= 0xEF) {
        n = 3;
        lo = b0 == 0xE0 ? 0xA0 : 0x80;
        hi = b0 == 0xED ? 0x9F : 0xBF;
    } else if (b0 >= 0xF0 && b0 <= 0xF4) {
        n = 4;
        lo = b0 == 0xF0 ? 0x90 : 0x80;
        hi = b0 == 0xF4 ? 0x8F : 0xBF;
    } else
        return 0;
    if (i + n > s.size() || byte(i + 1) < lo || byte(i + 1) > hi)
        return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xBF)
            return 0;
    return n;
}

} // namespace

std::string JsonWriter::quote(std::string_view s) {
    std::string out;
    out.reserve(s.size() + 2);
    out += '"';
    for (std::size_t i = 0; i < s.size();) {
        char const c = s[i];
        std::size_t const n = utf8Length(s, i);
        if (n == 0) {
            out += "\\uFFFD";
            ++i;
            continue;
        }
        if (n > 1) {
            out.append(s.substr(i, n));
            i += n;
            continue;
        }
        ++i;
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\b':
            out += "\\b";
            break;
        case '\f':
            out += "\\f";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20)
                out += fmt::format("\\u{:04x}", static_cast<unsigned char>(c));
            else
                out += c;
        }
    }
    out += '"';
    return out;
}

} // namespace regolith::core
