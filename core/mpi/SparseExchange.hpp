#pragma once
/// Sparse data exchange when receivers do NOT know their senders: the non-blocking consensus
/// algorithm NBX of Hoefler, Siebert & Lumsdaine, "Scalable communication protocols for
/// dynamic sparse data exchange", PPoPP 2010 (the "NBX" protocol).
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"

#include <mpi.h>

#include <concepts>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace regolith::core {

/// Sends one message to each rank whose `sendBuffer()` was asked for in this call, and
/// receives whatever other ranks sent here, without knowing beforehand who will send.
///
///     ex.sendBuffer(owner) << particle;   // any ranks, any number of times
///     ex.start();
///     ex.wait([&](int from, RecvBuffer& in) { ... });   // ascending `from`
///
/// A destination receives a message iff its `sendBuffer()` was called in this call, even if
/// the buffer stayed empty: an empty message arrives as an empty RecvBuffer (a notification).
/// A message to oneself is moved locally, without MPI.
///
/// NBX: synchronous sends (MPI_Issend) to every destination; then a loop that receives any
/// message with this call's tag (MPI_Improbe/MPI_Mrecv) and, once all own sends have been
/// matched, joins a non-blocking barrier (MPI_Ibarrier); the call ends when the barrier
/// completes, which proves that every message to this rank has been received. The two tags
/// alternate between consecutive calls: a rank that has left the barrier may already send its
/// next call's messages while a slower rank still probes for the current ones.
///
/// Counters (`counters()`): per call, messages = payload messages to other ranks (empty ones
/// included); bytes = their payload bytes; peers = number of other destination ranks. The
/// barrier's internal traffic is not counted.
///
/// Collectivity: the constructor, start() and wait() are COLLECTIVE over `comm` (every rank
/// calls them the same number of times, even with nothing to send). Not thread-safe.
class SparseExchange {
public:
    /// A received message: source rank and its payload.
    struct Message {
        int rank = -1;
        RecvBuffer buffer;
    };

    /// COLLECTIVE over `comm` (duplicates it).
    explicit SparseExchange(Comm const& comm);
    /// If a call is in flight, completes it (discarding what arrived), so that no rank waits
    /// forever in the barrier; this rank then still takes part in the call.
    ~SparseExchange();
    SparseExchange(SparseExchange const&) = delete;
    SparseExchange& operator=(SparseExchange const&) = delete;

    /// The buffer for rank `dest` in the current call (created on first use). Throws
    /// core::Error if `dest` is not in [0, size) or while a call is in flight.
    SendBuffer& sendBuffer(int dest);

    /// Starts the synchronous sends; returns at once. Throws core::Error if a call is already
    /// in flight or a buffer exceeds INT_MAX bytes.
    void start();

    /// Runs the NBX receive loop until the barrier completes, then hands every received
    /// message to `onMessage(rank, RecvBuffer&)` in ascending source rank. Throws core::Error
    /// without start(). COLLECTIVE over the communicator.
    template <class F>
    requires std::invocable<F&, int, RecvBuffer&>
    void wait(F&& onMessage) {
        for (auto& m : wait())
            onMessage(m.rank, m.buffer);
    }

    /// As wait(callback), returning the messages in ascending source rank.
    [[nodiscard]] std::vector<Message> wait();

    /// True between start() and wait().
    [[nodiscard]] bool inFlight() const { return m_inFlight; }
    [[nodiscard]] CommCounters const& counters() const { return m_counters; }
    /// Resets the counters (e.g. after set-up).
    void resetCounters() { m_counters.reset(); }

private:
    [[nodiscard]] int currentTag() const;

    Comm m_comm;
    std::map<int, SendBuffer> m_send; ///< destinations of the current call, ascending
    std::vector<MPI_Request> m_sendRequests;
    std::vector<Message> m_self; ///< the self message of the current call, if any
    std::uint64_t m_call = 0;    ///< calls started so far; its parity selects the tag
    bool m_inFlight = false;
    CommCounters m_counters;
};

} // namespace regolith::core
