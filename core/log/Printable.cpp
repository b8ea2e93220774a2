#include "core/log/Printable.hpp"

#include <fmt/format.h>

namespace regolith::core {

std::string printable(std::string_view text, std::size_t maxBytes) {
    bool const cut = text.size() > maxBytes;
    if (cut) {
        // Not inside a UTF-8 character: back to the start of the one cut.
        while (maxBytes > 0 && (static_cast<unsigned char>(text[maxBytes]) & 0xc0) == 0x80)
            --maxBytes;
        text = text.substr(0, maxBytes);
    }
    std::string out;
    out.reserve(text.size());
    for (char const c : text) {
        auto const byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f)
            out += fmt::format("\\x{:02x}", byte);
        else
            out += c;
    }
    if (cut)
        out += "...";
    return out;
}

} // namespace regolith::core
