#pragma once
/// Sparse data exchange when receivers do NOT know their senders: the non-blocking consensus
/// algorithm NBX of Hoefler, Siebert & Lumsdaine, "Scalable communication protocols for
/// dynamic sparse data exchange", PPoPP 2010 (the "NBX" protocol).
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"

#include <climits>
#include <mpi.h>

#include <array>
#include <concepts>
#include <cstdint>
#include <map>
#include <string>
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
/// A message to oneself is moved locally, without MPI and without size limit.
///
/// NBX: synchronous sends (MPI_Issend) to every destination; then a loop that receives any
/// message with this call's tag (MPI_Iprobe/MPI_Recv) and, once all own sends have been
/// matched, joins a non-blocking reduction (MPI_Iallreduce, where the paper uses an
/// MPI_Ibarrier: its completion proves the same, that every rank has entered it, so every
/// message to this rank has been received); the call ends when the reduction completes. The
/// reduction carries an error word, so an error found on one rank (a message over the limit)
/// reaches every rank at no extra latency. The two tags alternate between consecutive calls:
/// a rank that has left the reduction may already send its next call's messages while a
/// slower rank still probes for the current ones.
///
/// Counters (`counters()`): per call, messages = payload messages to other ranks (empty ones
/// included); bytes = their payload bytes; peers = number of other destination ranks. The
/// reduction's internal traffic is not counted, nor is a message over the limit (not sent).
///
/// Collectivity: the constructor, start() and wait() are COLLECTIVE over `comm` (every rank
/// calls them the same number of times, even with nothing to send). Not thread-safe.
///
/// Failure paths (none leaves another rank waiting while the run goes on):
///  - Misuse (sendBuffer() out of range or while in flight, start() twice, wait() without
///    start()): core::Error on the misusing rank only, before any MPI call; the object is
///    unchanged (a call in flight can still be completed by wait()). The other ranks wait in
///    the call until core::runApp aborts the job on that error.
///  - A buffer to another rank above maxMessageBytes(): start() does not send it and does
///    not throw; wait() completes the call and then throws core::Error on EVERY rank with the
///    same message, naming the lowest such (sender, destination) pair. The call's messages
///    are discarded everywhere; the object is usable afterwards.
///  - The callback of wait() throws: the call is already complete (messages are delivered
///    after the reduction), so the exception propagates, the remaining messages of this call
///    are dropped and the object is usable afterwards (asserted by the tests).
///  - Out of memory while receiving: wait() frees what this call received and completes the
///    call (still receiving, so that the other ranks' sends complete), then rethrows. If that
///    fails too, the object is unusable as after an MPI error.
///  - An MPI call fails (core::Error from Comm::check): MPI's state is then undefined; the
///    object frees its send requests without waiting (core/mpi/Requests.hpp), drops the
///    reduction request (MPI forbids freeing a nonblocking collective) and becomes unusable:
///    every later member call throws core::Error and the destructor makes no MPI call.
/// When an exception leaves start() or wait(), this object holds no active point-to-point
/// request, and no collective request except after an MPI error.
class SparseExchange {
public:
    /// A received message: source rank and its payload.
    struct Message {
        int rank = -1;
        RecvBuffer buffer;
    };

    /// The largest message MPI can send with an `int` count (no MPI-4 "_c" calls), in bytes.
    static constexpr std::uint64_t kMaxMessageBytes = INT_MAX;

    /// `maxMessageBytes`: the largest payload in bytes sent to another rank, in
    /// [1, kMaxMessageBytes] and equal on every rank (a lower limit catches runaway packing);
    /// throws core::Error on every rank, with the same message, otherwise.
    /// COLLECTIVE over `comm` (duplicates it, then one all-reduce).
    explicit SparseExchange(Comm const& comm, std::uint64_t maxMessageBytes = kMaxMessageBytes);
    /// If a call is in flight, completes it (discarding what arrived), so that no rank waits
    /// forever in the reduction; this rank then still takes part in the call. Never throws.
    ~SparseExchange();
    SparseExchange(SparseExchange const&) = delete;
    SparseExchange& operator=(SparseExchange const&) = delete;

    /// The buffer for rank `dest` in the current call (created on first use). Throws
    /// core::Error if `dest` is not in [0, size) or while a call is in flight.
    SendBuffer& sendBuffer(int dest);

    /// Starts the synchronous sends; returns at once. Throws core::Error if a call is already
    /// in flight (see the failure paths above).
    void start();

    /// Runs the NBX receive loop until the reduction completes, then hands every received
    /// message to `onMessage(rank, RecvBuffer&)` in ascending source rank. Throws core::Error
    /// without start(), or on every rank for a message over the limit. COLLECTIVE over the
    /// communicator.
    template <class F>
    requires std::invocable<F&, int, RecvBuffer&>
    void wait(F&& onMessage) {
        for (auto& m : wait())
            onMessage(m.rank, m.buffer);
    }

    /// As wait(callback), returning the messages in ascending source rank.
    [[nodiscard]] std::vector<Message> wait();

    /// Raises this rank's flag in the call in flight (between start() and wait()); after
    /// wait(), flagRaised() is true on every rank iff some rank raised it. The flag rides on
    /// the closing reduction, so it costs no message: e.g. "some rank has work for a second
    /// round", which lets every rank skip that round together. Throws core::Error without a
    /// call in flight.
    void raiseFlag();
    /// Whether some rank raised its flag in the last completed call.
    [[nodiscard]] bool flagRaised() const { return m_global[1] != 0; }

    /// True between start() and wait().
    [[nodiscard]] bool inFlight() const { return m_phase != Phase::Idle; }
    /// The limit given to the constructor, in bytes.
    [[nodiscard]] std::uint64_t maxMessageBytes() const { return m_maxMessageBytes; }
    [[nodiscard]] CommCounters const& counters() const { return m_counters; }
    /// Resets the counters (e.g. after set-up).
    void resetCounters() { m_counters.reset(); }

private:
    /// Where the call in flight is: sends not all matched yet, or in the closing reduction.
    enum class Phase { Idle, Sending, Closing };

    [[nodiscard]] int currentTag() const;
    /// Throws core::Error if an MPI error made this object unusable.
    void requireUsable() const;
    /// Comm::check, but on failure first gives up on every request (abandon()).
    void mpiCheck(int mpiResult, char const* what);
    /// After an MPI error: frees the sends, drops the reduction, marks the object unusable.
    void abandon(std::string const& why) noexcept;
    /// Runs the NBX loop from the current phase until the call is complete (Phase::Idle),
    /// appending what arrives to m_received. Resumable after an exception.
    void progress();
    /// Completes the call after an exception or in the destructor, discarding messages.
    void completeDiscarding() noexcept;

    Comm m_comm;
    std::uint64_t m_maxMessageBytes = kMaxMessageBytes;
    std::map<int, SendBuffer> m_send; ///< destinations of the current call, ascending
    std::vector<MPI_Request> m_sendRequests;
    MPI_Request m_closing = MPI_REQUEST_NULL; ///< the Iallreduce that ends a call
    /// Iallreduce input (MPI_MIN): {error key or kNoError, -1 if this rank raised the flag}.
    std::array<std::int64_t, 2> m_local{};
    std::array<std::int64_t, 2> m_global{}; ///< Iallreduce output: lowest error key, -any flag
    std::vector<Message> m_received;        ///< this call's messages so far (self included)
    std::uint64_t m_call = 0;               ///< calls started so far; parity selects the tag
    Phase m_phase = Phase::Idle;
    std::string m_mpiError; ///< non-empty once an MPI call failed: the object is unusable
    CommCounters m_counters;
};

} // namespace regolith::core
