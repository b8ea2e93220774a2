#pragma once
/// Text from a file or the user, made safe to print inside a message: a NUL byte would end
/// the message early (printf's %s, fputs), other control bytes would move the cursor or start
/// a terminal escape sequence.
#include <cstddef>
#include <string>
#include <string_view>

namespace regolith::core {

/// `text` with every control byte (below 0x20 and 0x7f, also a tab or line break) written as
/// "\xNN"; bytes from 0x80 on (UTF-8) stay. At most `maxBytes` bytes of `text` are shown, a
/// longer one ends in "...".
[[nodiscard]] std::string printable(std::string_view text,
                                    std::size_t maxBytes = std::string_view::npos);

} // namespace regolith::core
