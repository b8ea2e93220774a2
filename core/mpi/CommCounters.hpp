#pragma once
/// Traffic counters of one exchange object (NeighbourExchange, SparseExchange), so an app can
/// report `comm` {messages_per_step, bytes_per_step, max_peers} in its run summary.
///
/// What is counted: what THIS rank sent through MPI in one call of `start()`. A message to
/// oneself is handled locally and counted nowhere. Each exchange class states in its header
/// which of its messages count (e.g. NeighbourExchange counts its size messages too).
#include "core/mpi/Comm.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

namespace regolith::core {

/// Traffic of one exchange call on one rank.
struct CommStats {
    std::uint64_t messages = 0; ///< MPI point-to-point messages sent (self excluded)
    std::uint64_t bytes = 0;    ///< bytes in those messages
    int peers = 0;              ///< distinct other ranks sent at least one message

    /// Adds another exchange's call to this one: its messages and bytes, its peers if more.
    CommStats& operator+=(CommStats const& other) {
        messages += other.messages;
        bytes += other.bytes;
        peers = std::max(peers, other.peers);
        return *this;
    }
    bool operator==(CommStats const&) const = default;
};

/// Totals over several ranks (see CommCounters::reduce).
struct CommTotals {
    std::uint64_t messages = 0; ///< sum over ranks of all messages sent
    std::uint64_t bytes = 0;    ///< sum over ranks of all bytes sent
    std::uint64_t calls = 0;    ///< number of calls (maximum over ranks)
    int maxPeers = 0;           ///< largest `peers` of any single call on any rank
};

/// Counters of one exchange object on one rank: the last call plus cumulative totals.
class CommCounters {
public:
    /// Adds one call's traffic; it becomes `last()`.
    void record(CommStats const& call) {
        m_last = call;
        m_messages += call.messages;
        m_bytes += call.bytes;
        m_maxPeers = std::max(m_maxPeers, call.peers);
        ++m_calls;
    }
    /// Forgets everything (e.g. after set-up, so a summary covers the time loop only).
    void reset() { *this = CommCounters{}; }

    /// The most recent call (all zero before the first).
    [[nodiscard]] CommStats const& last() const { return m_last; }
    [[nodiscard]] std::uint64_t totalMessages() const { return m_messages; }
    [[nodiscard]] std::uint64_t totalBytes() const { return m_bytes; }
    /// Largest `peers` of any call so far.
    [[nodiscard]] int maxPeers() const { return m_maxPeers; }
    /// Number of calls recorded.
    [[nodiscard]] std::uint64_t calls() const { return m_calls; }

    /// Sums messages and bytes over the ranks of `comm`; calls and maxPeers are maxima.
    /// COLLECTIVE over `comm`. Divide by the number of steps for per-step figures.
    [[nodiscard]] CommTotals reduce(Comm const& comm) const {
        std::array<std::uint64_t, 2> sums{m_messages, m_bytes};
        comm.allReduceInPlace(std::span<std::uint64_t>(sums), ReduceOp::Sum);
        std::array<std::uint64_t, 2> maxima{m_calls, static_cast<std::uint64_t>(m_maxPeers)};
        comm.allReduceInPlace(std::span<std::uint64_t>(maxima), ReduceOp::Max);
        return CommTotals{sums[0], sums[1], maxima[0], static_cast<int>(maxima[1])};
    }

private:
    CommStats m_last;
    std::uint64_t m_messages = 0;
    std::uint64_t m_bytes = 0;
    std::uint64_t m_calls = 0;
    int m_maxPeers = 0;
};

} // namespace regolith::core
