#pragma once
/// Aggregated, non-blocking exchange with a KNOWN, symmetric set of peer ranks, in the style
/// of waLBerla's `BufferSystem` (one buffer per peer, sizes first, then payload).
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"

#include <climits>
#include <mpi.h>

#include <concepts>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace regolith::core {

/// One message per peer per call, built once from the peer list and reused for any number of
/// calls. Usage per call:
///
///     for (int p : ex.peers()) ex.sendBuffer(p) << stuff;
///     ex.start();                 // non-blocking
///     ... overlap work ...
///     ex.wait([&](int from, RecvBuffer& in) { ... });   // ascending `from`
///
/// The peer list is symmetric: this rank sends to and receives from exactly these ranks, and
/// each of them lists this rank (checked by the constructor). It may contain this rank: the
/// self message is moved locally, without MPI and without size limit. Every peer receives a
/// message each call, possibly empty; an empty message is delivered as an empty RecvBuffer.
///
/// Protocol per peer: a 64-bit size message (Tag::ExchangeSizes) always, then the payload
/// (Tag::ExchangeData) only if non-empty and within maxMessageBytes(). MPI's non-overtaking
/// rule (same source, tag and communicator) keeps consecutive calls apart, so no per-call tag
/// is needed.
///
/// Counters (`counters()`): per call, messages = one size message per other peer + one payload
/// message per non-empty buffer to another peer (a message over the limit is not sent and not
/// counted); bytes = 8 per size message + payload bytes; peers = number of other peers.
///
/// Collectivity: start() and wait() are collective over the peer group: every peer calls them
/// the same number of times. The constructor is COLLECTIVE over `comm`. Not thread-safe.
///
/// Failure paths (nothing here can leave a peer waiting while the run goes on: an error
/// either ends the call on every rank involved, or is a core::Error on which core::runApp
/// calls MPI_Abort):
///  - Peer lists invalid or asymmetric, or maxMessageBytes differing between ranks: the
///    constructor throws core::Error on EVERY rank, with the same message naming one rank
///    (invalid list) or one rank pair (asymmetry).
///  - Misuse (sendBuffer() of a non-peer or while in flight, start() twice, wait() without
///    start()): core::Error on the misusing rank only, before any MPI call; the object is
///    unchanged (a call in flight stays in flight and can still be completed by wait()).
///  - A buffer to another rank above maxMessageBytes(): start() does not throw; it sends the
///    size (so the receiver knows) but not the payload. wait() then completes the call and
///    throws core::Error on the sender (delivering nothing) and on that receiver (after
///    delivering the lower-ranked messages), both with the message naming sender, receiver
///    and size. Other peers receive everything. The object is usable afterwards.
///  - The callback of wait() throws: wait() completes the call, discarding the undelivered
///    messages, and rethrows. The object is usable afterwards (asserted by the tests).
///  - An MPI call fails (core::Error from Comm::check): MPI's state is then undefined, so the
///    object cancels its posted receives, frees its posted sends without waiting (see
///    core/mpi/Requests.hpp) and becomes unusable: every later member call throws core::Error
///    and the destructor makes no MPI call.
///  - Out of memory (std::bad_alloc) in wait() while growing a receive buffer: the call is
///    completed as far as possible and the exception rethrown; the sender of the message that
///    could not be received may wait until core::runApp aborts the job.
/// When an exception leaves start() or wait(), this object holds no active MPI request.
class NeighbourExchange {
public:
    /// A received message: source rank and its payload.
    struct Message {
        int rank = -1;
        RecvBuffer buffer;
    };

    /// The largest message MPI can send with an `int` count (no MPI-4 "_c" calls), in bytes.
    static constexpr std::uint64_t kMaxMessageBytes = INT_MAX;

    /// Pre: `peers` strictly ascending, each in [0, comm.size()), symmetric over all ranks;
    /// `maxMessageBytes` in [1, kMaxMessageBytes] and equal on every rank (the largest payload
    /// in bytes sent to another rank in one call; a lower limit catches runaway packing).
    /// Throws core::Error on every rank, with the same message, if any rank breaks this.
    /// COLLECTIVE over `comm` (duplicates it, then one reduce-scatter, one message per peer
    /// and one all-reduce; see peersAreSymmetric()).
    NeighbourExchange(Comm const& comm, std::vector<int> peers,
                      std::uint64_t maxMessageBytes = kMaxMessageBytes);
    /// If a call is in flight, completes it (discarding what arrived): buffers that MPI still
    /// reads from or writes into must not be freed, and peers must not wait for this rank.
    /// Never throws.
    ~NeighbourExchange();
    NeighbourExchange(NeighbourExchange const&) = delete;
    NeighbourExchange& operator=(NeighbourExchange const&) = delete;

    /// Checks that the peer lists of all ranks are symmetric (r lists q iff q lists r) and in
    /// range; order and duplicates do not matter. Returns the same answer on every rank.
    /// Cost: O(P) memory and one reduce-scatter per rank, plus one empty message per listed
    /// peer (the "personalized census" of Hoefler, Siebert & Lumsdaine, PPoPP 2010). The same
    /// check runs in the constructor. COLLECTIVE over `comm` (duplicates it).
    [[nodiscard]] static bool peersAreSymmetric(Comm const& comm, std::span<int const> peers);

    /// The buffer for `peer` in the current call. Throws core::Error if `peer` is not in the
    /// peer list, or while a call is in flight (between start() and wait()).
    SendBuffer& sendBuffer(int peer);

    /// Posts the receives for sizes, sends sizes and payloads; returns at once. Throws
    /// core::Error if a call is already in flight (see the failure paths above).
    void start();

    /// Completes the call and hands each peer's message to `onMessage(rank, RecvBuffer&)`, in
    /// ascending rank order; a message is delivered as soon as it and all lower-ranked ones
    /// have arrived, so unpacking overlaps the arrival of later messages. The send buffers are
    /// empty afterwards. If `onMessage` throws, the call is completed before rethrowing.
    /// Throws core::Error without start(), or for a message over the limit (see above).
    template <class F>
    requires std::invocable<F&, int, RecvBuffer&>
    void wait(F&& onMessage) {
        auto deliver = [&onMessage](int rank, RecvBuffer& b) { onMessage(rank, b); };
        waitImpl(Delivery(deliver));
    }

    /// As wait(callback), returning all messages in ascending rank order.
    [[nodiscard]] std::vector<Message> wait();

    /// True between start() and wait().
    [[nodiscard]] bool inFlight() const { return m_inFlight; }
    [[nodiscard]] std::vector<int> const& peers() const { return m_peers; }
    /// The limit given to the constructor, in bytes.
    [[nodiscard]] std::uint64_t maxMessageBytes() const { return m_maxMessageBytes; }
    [[nodiscard]] CommCounters const& counters() const { return m_counters; }
    /// Resets the counters (e.g. after set-up).
    void resetCounters() { m_counters.reset(); }

private:
    /// Type-erased, non-owning reference to the delivery callback.
    class Delivery {
    public:
        template <class G>
        explicit Delivery(G& g)
            : m_object(&g)
            , m_call([](void* o, int r, RecvBuffer& b) { (*static_cast<G*>(o))(r, b); }) {}
        void operator()(int rank, RecvBuffer& b) const { m_call(m_object, rank, b); }

    private:
        void* m_object;
        void (*m_call)(void*, int, RecvBuffer&);
    };

    void waitImpl(Delivery deliver);
    /// Index of `peer` in m_peers, or -1.
    [[nodiscard]] int indexOf(int peer) const;
    /// Handles the completion of request `i` of m_requests (size or payload receive).
    void onCompleted(std::size_t i);
    /// Throws core::Error if an MPI error made this object unusable.
    void requireUsable() const;
    /// Comm::check, but on failure first gives up on every request (abandon()).
    void mpiCheck(int mpiResult, char const* what);
    /// After an MPI error: cancels the receives, frees the sends, marks the object unusable.
    void abandon(std::string const& why) noexcept;
    /// Completes every outstanding request, discarding payloads; ends the call (cleanup path).
    void drain() noexcept;
    /// Clears the per-call state after the call's requests are all complete.
    void endCall() noexcept;

    Comm m_comm;
    std::vector<int> m_peers;
    std::uint64_t m_maxMessageBytes = kMaxMessageBytes;
    int m_selfIndex = -1;
    std::vector<SendBuffer> m_send;
    std::vector<std::uint64_t> m_sendSizes;
    std::vector<std::uint64_t> m_recvSizes;
    std::vector<std::vector<std::byte>> m_recv;
    std::vector<bool> m_ready;
    /// [0, n): size receives, [n, 2n): payload receives, indexed like m_peers.
    std::vector<MPI_Request> m_requests;
    std::vector<int> m_done; ///< MPI_Waitsome indices, sized like m_requests
    std::vector<MPI_Request> m_sendRequests;
    std::string m_sendError; ///< this call: a buffer over the limit (thrown by wait())
    std::string m_mpiError;  ///< non-empty once an MPI call failed: the object is unusable
    bool m_inFlight = false;
    CommCounters m_counters;
};

} // namespace regolith::core
