#pragma once
/// Aggregated, non-blocking exchange with a KNOWN, symmetric set of peer ranks, in the style
/// of waLBerla's `BufferSystem` (one buffer per peer, sizes first, then payload).
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"

#include <mpi.h>

#include <concepts>
#include <cstdint>
#include <span>
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
/// each of them lists this rank. It may contain this rank: the self message is moved locally,
/// without MPI. Every peer receives a message each call, possibly empty; an empty message is
/// delivered as an empty RecvBuffer.
///
/// Protocol per peer: a 64-bit size message (Tag::ExchangeSizes) always, then the payload
/// (Tag::ExchangeData) only if non-empty. MPI's non-overtaking rule (same source, tag and
/// communicator) keeps consecutive calls apart, so no per-call tag is needed.
///
/// Counters (`counters()`): per call, messages = one size message per other peer + one payload
/// message per non-empty buffer to another peer; bytes = 8 per size message + payload bytes;
/// peers = number of other peers (all of them get a size message).
///
/// Collectivity: start() and wait() are collective over the peer group: every peer calls them
/// the same number of times. The constructor is COLLECTIVE over `comm` (it duplicates it).
/// Not thread-safe.
class NeighbourExchange {
public:
    /// A received message: source rank and its payload.
    struct Message {
        int rank = -1;
        RecvBuffer buffer;
    };

    /// Pre: `peers` strictly ascending, each in [0, comm.size()); throws core::Error otherwise.
    /// COLLECTIVE over `comm`.
    NeighbourExchange(Comm const& comm, std::vector<int> peers);
    /// If a call is in flight, completes it (discarding what arrived): buffers that MPI still
    /// reads from or writes into must not be freed.
    ~NeighbourExchange();
    NeighbourExchange(NeighbourExchange const&) = delete;
    NeighbourExchange& operator=(NeighbourExchange const&) = delete;

    /// Checks that the peer lists of all ranks are symmetric (r lists q iff q lists r), with
    /// an all-to-all of one flag per rank pair. Returns the same answer on every rank.
    /// COLLECTIVE over `comm`. Meant for set-up and tests, not every step.
    [[nodiscard]] static bool peersAreSymmetric(Comm const& comm, std::span<int const> peers);

    /// The buffer for `peer` in the current call. Throws core::Error if `peer` is not in the
    /// peer list, or while a call is in flight (between start() and wait()).
    SendBuffer& sendBuffer(int peer);

    /// Posts the receives for sizes, sends sizes and non-empty payloads; returns at once.
    /// Throws core::Error if a call is already in flight or a buffer exceeds INT_MAX bytes.
    void start();

    /// Completes the call and hands each peer's message to `onMessage(rank, RecvBuffer&)`, in
    /// ascending rank order; a message is delivered as soon as it and all lower-ranked ones
    /// have arrived, so unpacking overlaps the arrival of later messages. The send buffers are
    /// empty afterwards. If `onMessage` throws, the call is completed before rethrowing.
    /// Throws core::Error without start().
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
    /// Completes every outstanding request, ignoring errors (cleanup path).
    void drain() noexcept;

    Comm m_comm;
    std::vector<int> m_peers;
    int m_selfIndex = -1;
    std::vector<SendBuffer> m_send;
    std::vector<std::uint64_t> m_sendSizes;
    std::vector<std::uint64_t> m_recvSizes;
    std::vector<std::vector<std::byte>> m_recv;
    std::vector<bool> m_ready;
    /// [0, n): size receives, [n, 2n): payload receives, indexed like m_peers.
    std::vector<MPI_Request> m_requests;
    std::vector<MPI_Request> m_sendRequests;
    bool m_inFlight = false;
    CommCounters m_counters;
};

} // namespace regolith::core
