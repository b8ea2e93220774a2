#include "core/mpi/NeighbourExchange.hpp"

#include "core/Error.hpp"
#include "core/mpi/Requests.hpp"
#include "core/mpi/Tags.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>
#include <new>

namespace regolith::core {

namespace {

constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();

/// What is wrong with one rank's own list and limit, "" if nothing. Local.
std::string localListError(std::span<int const> peers, int size, bool strictlyAscending,
                           std::uint64_t limit) {
    for (std::size_t i = 0; i < peers.size(); ++i) {
        int const p = peers[i];
        if (p < 0 || p >= size)
            return fmt::format("peer {} out of range [0, {})", p, size);
        if (strictlyAscending && i > 0 && peers[i - 1] >= p)
            return fmt::format("peer list must be strictly ascending ({} after {})", p,
                               peers[i - 1]);
    }
    if (limit == 0 || limit > NeighbourExchange::kMaxMessageBytes)
        return fmt::format("maxMessageBytes {} not in [1, {}]", limit,
                           NeighbourExchange::kMaxMessageBytes);
    return {};
}

/// The ranks that list this rank, ascending, when `listedBy` of them do: each rank sends an
/// empty note to every rank it lists, and this rank receives exactly `listedBy` notes.
/// COLLECTIVE over `comm`. On an exception no send request is left active.
std::vector<int> censusSources(Comm const& comm, std::vector<int> const& listed, int listedBy) {
    int const tag = toInt(Tag::ExchangePeerCheck);
    std::vector<MPI_Request> sends(listed.size(), MPI_REQUEST_NULL);
    std::vector<int> sources;
    char const note = 0;
    try {
        sources.reserve(static_cast<std::size_t>(listedBy));
        for (std::size_t k = 0; k < listed.size(); ++k)
            Comm::check(MPI_Isend(&note, 0, MPI_BYTE, listed[k], tag, comm.raw(), &sends[k]),
                        "MPI_Isend");
        for (int k = 0; k < listedBy; ++k) {
            char sink = 0;
            MPI_Status status;
            Comm::check(MPI_Recv(&sink, 0, MPI_BYTE, MPI_ANY_SOURCE, tag, comm.raw(), &status),
                        "MPI_Recv");
            sources.push_back(status.MPI_SOURCE);
        }
        Comm::check(MPI_Waitall(static_cast<int>(sends.size()), sends.data(), MPI_STATUSES_IGNORE),
                    "MPI_Waitall");
    } catch (...) {
        releaseSends(sends);
        throw;
    }
    std::sort(sources.begin(), sources.end());
    return sources;
}

/// The one collective peer-list check behind the constructor and peersAreSymmetric(): "" if
/// every rank's list is valid, the lists are symmetric and the limits agree, else a message
/// that is the same on every rank. COLLECTIVE over `comm`.
///
/// Symmetry is tested with the personalized census (PCX) of Hoefler, Siebert & Lumsdaine,
/// "Scalable communication protocols for dynamic sparse data exchange", PPoPP 2010: a
/// reduce-scatter of one flag per rank tells each rank how many ranks list it; each rank then
/// receives that many notes and compares their senders with its own list. Equal counts alone
/// would not do (a directed cycle has in-degree = out-degree everywhere). The first
/// disagreement in (lister, listed) order is agreed on with one all-reduce.
std::string agreeOnPeerLists(Comm const& comm, std::span<int const> peers,
                             std::string const& localError, std::uint64_t limit) {
    int const p = comm.size();
    int const me = comm.rank();
    // A self link is symmetric by itself; out-of-range entries are reported as localError.
    std::vector<int> listed;
    for (int const q : peers)
        if (q >= 0 && q < p && q != me)
            listed.push_back(q);
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());

    std::vector<int> flags(static_cast<std::size_t>(p), 0);
    for (int const q : listed)
        flags[static_cast<std::size_t>(q)] = 1;
    int listedBy = 0;
    Comm::check(MPI_Reduce_scatter_block(flags.data(), &listedBy, 1, MPI_INT, MPI_SUM, comm.raw()),
                "MPI_Reduce_scatter_block");
    std::vector<int> const listers = censusSources(comm, listed, listedBy);

    // Key a * p + b: "rank a lists rank b, but b does not list a". Both ranks see it.
    auto const key = [p](int a, int b) { return std::int64_t{a} * p + b; };
    std::int64_t asymmetry = kNone;
    std::vector<int> diff;
    std::set_difference(listed.begin(), listed.end(), listers.begin(), listers.end(),
                        std::back_inserter(diff));
    for (int const q : diff)
        asymmetry = std::min(asymmetry, key(me, q));
    diff.clear();
    std::set_difference(listers.begin(), listers.end(), listed.begin(), listed.end(),
                        std::back_inserter(diff));
    for (int const s : diff)
        asymmetry = std::min(asymmetry, key(s, me));

    auto const clampedLimit = static_cast<std::int64_t>(
        std::min<std::uint64_t>(limit, std::numeric_limits<std::int64_t>::max()));
    std::array<std::int64_t, 4> agreed{localError.empty() ? std::int64_t{p} : std::int64_t{me},
                                       asymmetry, clampedLimit, -clampedLimit};
    comm.allReduceInPlace(std::span<std::int64_t>(agreed), ReduceOp::Min);

    if (agreed[0] < p) { // the lowest rank with an invalid list tells everyone what is wrong
        int const bad = static_cast<int>(agreed[0]);
        std::string what = localError;
        comm.broadcast(what, bad);
        return fmt::format("NeighbourExchange: rank {}: {}", bad, what);
    }
    if (agreed[2] != -agreed[3])
        return fmt::format("NeighbourExchange: maxMessageBytes differs between ranks ({} to {})",
                           agreed[2], -agreed[3]);
    if (agreed[1] != kNone) {
        auto const a = agreed[1] / p;
        auto const b = agreed[1] % p;
        return fmt::format("NeighbourExchange: asymmetric peer lists: rank {} lists rank {}, but "
                           "rank {} does not list rank {}",
                           a, b, b, a);
    }
    return {};
}

std::string tooLargeMessage(int from, int to, std::uint64_t bytes, std::uint64_t limit) {
    return fmt::format("NeighbourExchange: rank {} has a {}-byte message for rank {}, above the "
                       "limit of {} bytes",
                       from, bytes, to, limit);
}

} // namespace

NeighbourExchange::NeighbourExchange(Comm const& comm, std::vector<int> peers,
                                     std::uint64_t maxMessageBytes)
    : m_comm(comm.duplicate())
    , m_peers(std::move(peers))
    , m_maxMessageBytes(maxMessageBytes) {
    // Checked after the (collective) duplicate and agreed on by all ranks, so that every rank
    // throws the same error and none is left waiting in a later collective.
    std::string const error = agreeOnPeerLists(
        m_comm, m_peers, localListError(m_peers, m_comm.size(), true, maxMessageBytes),
        maxMessageBytes);
    if (!error.empty())
        throw Error(error);
    std::size_t const n = m_peers.size();
    m_selfIndex = indexOf(m_comm.rank());
    m_send.resize(n);
    m_sendSizes.assign(n, 0);
    m_recvSizes.assign(n, 0);
    m_recv.resize(n);
    m_ready.assign(n, false);
    m_requests.assign(2 * n, MPI_REQUEST_NULL);
    m_done.assign(2 * n, 0);
    m_sendRequests.reserve(2 * n); // start() then never allocates
}

NeighbourExchange::~NeighbourExchange() {
    if (m_inFlight)
        drain();
}

bool NeighbourExchange::peersAreSymmetric(Comm const& comm, std::span<int const> peers) {
    Comm const own = comm.duplicate(); // the census traffic cannot meet the caller's messages
    return agreeOnPeerLists(own, peers, localListError(peers, own.size(), false, 1), 1).empty();
}

int NeighbourExchange::indexOf(int peer) const {
    auto const it = std::lower_bound(m_peers.begin(), m_peers.end(), peer);
    if (it == m_peers.end() || *it != peer)
        return -1;
    return static_cast<int>(it - m_peers.begin());
}

void NeighbourExchange::requireUsable() const {
    if (!m_mpiError.empty())
        throw Error("NeighbourExchange unusable after an MPI error: " + m_mpiError);
}

void NeighbourExchange::mpiCheck(int mpiResult, char const* what) {
    if (mpiResult == MPI_SUCCESS)
        return;
    try {
        Comm::check(mpiResult, what);
    } catch (Error const& e) {
        abandon(e.what());
        throw;
    }
}

void NeighbourExchange::abandon(std::string const& why) noexcept {
    cancelReceives(m_requests);
    releaseSends(m_sendRequests);
    m_sendRequests.clear();
    try {
        m_mpiError = why;
    } catch (...) { // out of memory for the text: still mark the object unusable
        m_mpiError.clear();
        m_mpiError.push_back('?');
    }
    m_inFlight = false;
}

SendBuffer& NeighbourExchange::sendBuffer(int peer) {
    requireUsable();
    if (m_inFlight)
        throw Error("NeighbourExchange::sendBuffer called between start() and wait()");
    int const i = indexOf(peer);
    if (i < 0)
        throw Error(fmt::format("NeighbourExchange: rank {} is not a peer of rank {} ({} peers)",
                                peer, m_comm.rank(), m_peers.size()));
    return m_send[static_cast<std::size_t>(i)];
}

void NeighbourExchange::start() {
    requireUsable();
    if (m_inFlight)
        throw Error("NeighbourExchange::start called twice without wait()");
    // Nothing below allocates (every vector was sized by the constructor), so only an MPI
    // error can throw, and mpiCheck() then gives up on whatever was posted.
    std::size_t const n = m_peers.size();
    MPI_Comm const raw = m_comm.raw();
    std::fill(m_ready.begin(), m_ready.end(), false);
    m_sendRequests.clear();
    m_sendError.clear();
    // Receives first, so that sizes can land directly in place.
    for (std::size_t i = 0; i < n; ++i) {
        if (static_cast<int>(i) == m_selfIndex)
            continue;
        mpiCheck(MPI_Irecv(&m_recvSizes[i], 1, MPI_UINT64_T, m_peers[i], toInt(Tag::ExchangeSizes),
                           raw, &m_requests[i]),
                 "MPI_Irecv");
    }
    CommStats stats;
    for (std::size_t i = 0; i < n; ++i) {
        if (static_cast<int>(i) == m_selfIndex) {
            m_recv[i] = m_send[i].release();
            m_recvSizes[i] = m_recv[i].size();
            m_ready[i] = true;
            continue;
        }
        // The size goes out even when the payload cannot: the receiver learns of the error
        // from it instead of waiting for a payload that never comes.
        m_sendSizes[i] = m_send[i].size();
        mpiCheck(MPI_Isend(&m_sendSizes[i], 1, MPI_UINT64_T, m_peers[i], toInt(Tag::ExchangeSizes),
                           raw, &m_sendRequests.emplace_back()),
                 "MPI_Isend");
        stats.messages += 1;
        stats.bytes += sizeof(std::uint64_t);
        ++stats.peers;
        if (m_sendSizes[i] > m_maxMessageBytes) {
            if (m_sendError.empty())
                m_sendError =
                    tooLargeMessage(m_comm.rank(), m_peers[i], m_sendSizes[i], m_maxMessageBytes);
        } else if (m_sendSizes[i] > 0) {
            mpiCheck(MPI_Isend(m_send[i].data(), static_cast<int>(m_sendSizes[i]), MPI_BYTE,
                               m_peers[i], toInt(Tag::ExchangeData), raw,
                               &m_sendRequests.emplace_back()),
                     "MPI_Isend");
            stats.messages += 1;
            stats.bytes += m_sendSizes[i];
        }
    }
    m_counters.record(stats);
    m_inFlight = true;
}

void NeighbourExchange::onCompleted(std::size_t i) {
    std::size_t const n = m_peers.size();
    if (i >= n) { // payload arrived
        m_ready[i - n] = true;
        return;
    }
    std::uint64_t const size = m_recvSizes[i];
    if (size == 0 || size > m_maxMessageBytes) { // over the limit: no payload follows
        m_ready[i] = true;
        return;
    }
    // The storage only grows: zero-filled once, not for every message.
    if (m_recv[i].size() < size)
        m_recv[i].resize(static_cast<std::size_t>(size));
    mpiCheck(MPI_Irecv(m_recv[i].data(), static_cast<int>(size), MPI_BYTE, m_peers[i],
                       toInt(Tag::ExchangeData), m_comm.raw(), &m_requests[n + i]),
             "MPI_Irecv");
}

void NeighbourExchange::waitImpl(Delivery deliver) {
    requireUsable();
    if (!m_inFlight)
        throw Error("NeighbourExchange::wait called without start()");
    if (!m_sendError.empty()) { // this rank's own oversized buffer: see the header
        std::string const error = m_sendError;
        drain();
        throw Error(error);
    }
    std::size_t const n = m_peers.size();
    try {
        std::size_t next = 0;
        while (next < n) {
            if (m_ready[next]) {
                if (static_cast<int>(next) != m_selfIndex && m_recvSizes[next] > m_maxMessageBytes)
                    throw Error(tooLargeMessage(m_peers[next], m_comm.rank(), m_recvSizes[next],
                                                m_maxMessageBytes));
                RecvBuffer in(std::move(m_recv[next]), m_recvSizes[next]);
                int const from = m_peers[next];
                deliver(from, in);
                m_recv[next] = in.takeStorage(); // for the next call (empty if moved out)
                ++next;
                continue;
            }
            // Something is outstanding, else peer `next` would be ready.
            int count = 0;
            mpiCheck(MPI_Waitsome(static_cast<int>(m_requests.size()), m_requests.data(), &count,
                                  m_done.data(), MPI_STATUSES_IGNORE),
                     "MPI_Waitsome");
            if (count == MPI_UNDEFINED)
                throw Error("NeighbourExchange: internal error, waiting with nothing posted");
            for (int k = 0; k < count; ++k)
                onCompleted(static_cast<std::size_t>(m_done[static_cast<std::size_t>(k)]));
        }
        mpiCheck(MPI_Waitall(static_cast<int>(m_sendRequests.size()), m_sendRequests.data(),
                             MPI_STATUSES_IGNORE),
                 "MPI_Waitall");
    } catch (...) {
        drain(); // after an MPI error abandon() has already ended the call
        throw;
    }
    endCall();
}

std::vector<NeighbourExchange::Message> NeighbourExchange::wait() {
    std::vector<Message> out;
    out.reserve(m_peers.size());
    wait([&out](int rank, RecvBuffer& b) { out.push_back(Message{rank, std::move(b)}); });
    return out;
}

void NeighbourExchange::drain() noexcept {
    if (!m_inFlight)
        return;
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (finalised) { // the handles died with MPI
        std::fill(m_requests.begin(), m_requests.end(), MPI_REQUEST_NULL);
        m_sendRequests.clear();
        endCall();
        return;
    }
    try {
        for (;;) {
            int count = 0;
            mpiCheck(MPI_Waitsome(static_cast<int>(m_requests.size()), m_requests.data(), &count,
                                  m_done.data(), MPI_STATUSES_IGNORE),
                     "MPI_Waitsome");
            if (count == MPI_UNDEFINED)
                break;
            for (int k = 0; k < count; ++k) {
                try {
                    onCompleted(static_cast<std::size_t>(m_done[static_cast<std::size_t>(k)]));
                } catch (std::bad_alloc const&) { // no memory for this payload: left unreceived
                }
            }
        }
        mpiCheck(MPI_Waitall(static_cast<int>(m_sendRequests.size()), m_sendRequests.data(),
                             MPI_STATUSES_IGNORE),
                 "MPI_Waitall");
    } catch (...) { // an MPI error: mpiCheck() has given up on every request
    }
    endCall();
}

void NeighbourExchange::endCall() noexcept {
    m_sendRequests.clear();
    for (auto& b : m_send) // both keep their storage for the next call
        b.clear();
    m_sendError.clear();
    m_inFlight = false;
}

} // namespace regolith::core
