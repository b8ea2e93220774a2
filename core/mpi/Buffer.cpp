#include "core/mpi/Buffer.hpp"

#include <fmt/format.h>

namespace regolith::core {

std::vector<std::byte> SendBuffer::release() {
    m_data.resize(m_size);
    m_size = 0;
    return std::move(m_data);
}

void SendBuffer::grow(std::size_t n) {
    m_data.resize(std::max(2 * m_data.size(), m_size + n));
}

void RecvBuffer::throwShort(std::size_t n, char const* what) const {
    throw BufferError(fmt::format("message buffer too short: reading {} ({} bytes) at offset {} "
                                  "of a {}-byte buffer, {} bytes remain",
                                  what, n, m_pos, m_size, remaining()));
}

void RecvBuffer::throwCorrupt(std::uint64_t n, std::size_t bytes, char const* what) const {
    throw BufferError(fmt::format("corrupt message buffer: {} claims {} elements of {} bytes at "
                                  "offset {}, but only {} bytes remain",
                                  what, n, bytes, m_pos, remaining()));
}

} // namespace regolith::core
