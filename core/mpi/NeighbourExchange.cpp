#include "core/mpi/NeighbourExchange.hpp"

#include "core/Error.hpp"
#include "core/mpi/Tags.hpp"

#include <climits>
#include <fmt/format.h>

#include <algorithm>

namespace regolith::core {

namespace {

constexpr std::uint64_t kMaxMessageBytes = INT_MAX; // MPI counts are int (no MPI-4 "_c" calls)

} // namespace

NeighbourExchange::NeighbourExchange(Comm const& comm, std::vector<int> peers)
    : m_comm(comm.duplicate())
    , m_peers(std::move(peers)) {
    // Validated after the (collective) duplicate, so a rank with a bad list cannot leave the
    // others waiting in MPI_Comm_dup.
    for (std::size_t i = 0; i < m_peers.size(); ++i) {
        int const p = m_peers[i];
        if (p < 0 || p >= m_comm.size())
            throw Error(
                fmt::format("NeighbourExchange: peer {} out of range [0, {})", p, m_comm.size()));
        if (i > 0 && m_peers[i - 1] >= p)
            throw Error("NeighbourExchange: peer list must be strictly ascending");
        if (p == m_comm.rank())
            m_selfIndex = static_cast<int>(i);
    }
    std::size_t const n = m_peers.size();
    m_send.resize(n);
    m_sendSizes.assign(n, 0);
    m_recvSizes.assign(n, 0);
    m_recv.resize(n);
    m_ready.assign(n, false);
    m_requests.assign(2 * n, MPI_REQUEST_NULL);
    m_sendRequests.reserve(2 * n);
}

NeighbourExchange::~NeighbourExchange() {
    if (m_inFlight)
        drain();
}

bool NeighbourExchange::peersAreSymmetric(Comm const& comm, std::span<int const> peers) {
    auto const p = static_cast<std::size_t>(comm.size());
    std::vector<int> iSendTo(p, 0);
    bool valid = true;
    for (int const q : peers) {
        if (q < 0 || q >= comm.size())
            valid = false;
        else
            iSendTo[static_cast<std::size_t>(q)] = 1;
    }
    // After the all-to-all, entry q says whether rank q lists this rank.
    std::vector<int> listsMe(p, 0);
    Comm::check(MPI_Alltoall(iSendTo.data(), 1, MPI_INT, listsMe.data(), 1, MPI_INT, comm.raw()),
                "MPI_Alltoall");
    return comm.allTrue(valid && iSendTo == listsMe);
}

int NeighbourExchange::indexOf(int peer) const {
    auto const it = std::lower_bound(m_peers.begin(), m_peers.end(), peer);
    if (it == m_peers.end() || *it != peer)
        return -1;
    return static_cast<int>(it - m_peers.begin());
}

SendBuffer& NeighbourExchange::sendBuffer(int peer) {
    if (m_inFlight)
        throw Error("NeighbourExchange::sendBuffer called between start() and wait()");
    int const i = indexOf(peer);
    if (i < 0)
        throw Error(fmt::format("NeighbourExchange: rank {} is not a peer of rank {} ({} peers)",
                                peer, m_comm.rank(), m_peers.size()));
    return m_send[static_cast<std::size_t>(i)];
}

void NeighbourExchange::start() {
    if (m_inFlight)
        throw Error("NeighbourExchange::start called twice without wait()");
    std::size_t const n = m_peers.size();
    for (std::size_t i = 0; i < n; ++i)
        if (m_send[i].size() > kMaxMessageBytes)
            throw Error(fmt::format("NeighbourExchange: {}-byte message to rank {} exceeds the "
                                    "MPI limit of {} bytes",
                                    m_send[i].size(), m_peers[i], kMaxMessageBytes));

    MPI_Comm const raw = m_comm.raw();
    std::fill(m_ready.begin(), m_ready.end(), false);
    m_sendRequests.clear();
    // Receives first, so that sizes can land directly in place.
    for (std::size_t i = 0; i < n; ++i) {
        if (static_cast<int>(i) == m_selfIndex)
            continue;
        Comm::check(MPI_Irecv(&m_recvSizes[i], 1, MPI_UINT64_T, m_peers[i],
                              toInt(Tag::ExchangeSizes), raw, &m_requests[i]),
                    "MPI_Irecv");
    }
    CommStats stats;
    for (std::size_t i = 0; i < n; ++i) {
        if (static_cast<int>(i) == m_selfIndex) {
            m_recv[i] = m_send[i].release();
            m_ready[i] = true;
            continue;
        }
        m_sendSizes[i] = m_send[i].size();
        Comm::check(MPI_Isend(&m_sendSizes[i], 1, MPI_UINT64_T, m_peers[i],
                              toInt(Tag::ExchangeSizes), raw, &m_sendRequests.emplace_back()),
                    "MPI_Isend");
        stats.messages += 1;
        stats.bytes += sizeof(std::uint64_t);
        ++stats.peers;
        if (m_sendSizes[i] > 0) {
            Comm::check(MPI_Isend(m_send[i].data(), static_cast<int>(m_sendSizes[i]), MPI_BYTE,
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
    if (size == 0) {
        m_recv[i].clear();
        m_ready[i] = true;
        return;
    }
    if (size > kMaxMessageBytes)
        throw Error(
            fmt::format("NeighbourExchange: corrupt size {} from rank {}", size, m_peers[i]));
    m_recv[i].resize(static_cast<std::size_t>(size));
    Comm::check(MPI_Irecv(m_recv[i].data(), static_cast<int>(size), MPI_BYTE, m_peers[i],
                          toInt(Tag::ExchangeData), m_comm.raw(), &m_requests[n + i]),
                "MPI_Irecv");
}

void NeighbourExchange::waitImpl(Delivery deliver) {
    if (!m_inFlight)
        throw Error("NeighbourExchange::wait called without start()");
    std::size_t const n = m_peers.size();
    try {
        std::vector<int> done(m_requests.size());
        std::size_t next = 0;
        while (next < n) {
            if (m_ready[next]) {
                RecvBuffer in(std::move(m_recv[next]));
                m_recv[next] = {};
                int const from = m_peers[next];
                ++next;
                deliver(from, in);
                continue;
            }
            // Something is outstanding, else peer `next` would be ready.
            int count = 0;
            Comm::check(MPI_Waitsome(static_cast<int>(m_requests.size()), m_requests.data(), &count,
                                     done.data(), MPI_STATUSES_IGNORE),
                        "MPI_Waitsome");
            for (int k = 0; k < count; ++k)
                onCompleted(static_cast<std::size_t>(done[static_cast<std::size_t>(k)]));
        }
        Comm::check(MPI_Waitall(static_cast<int>(m_sendRequests.size()), m_sendRequests.data(),
                                MPI_STATUSES_IGNORE),
                    "MPI_Waitall");
    } catch (...) {
        drain();
        throw;
    }
    for (auto& b : m_send)
        b.clear();
    m_inFlight = false;
}

std::vector<NeighbourExchange::Message> NeighbourExchange::wait() {
    std::vector<Message> out;
    out.reserve(m_peers.size());
    wait([&out](int rank, RecvBuffer& b) { out.push_back(Message{rank, std::move(b)}); });
    return out;
}

void NeighbourExchange::drain() noexcept {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (finalised) {
        m_inFlight = false;
        return;
    }
    std::vector<int> done(m_requests.size());
    for (;;) {
        int count = 0;
        if (MPI_Waitsome(static_cast<int>(m_requests.size()), m_requests.data(), &count,
                         done.data(), MPI_STATUSES_IGNORE) != MPI_SUCCESS ||
            count == MPI_UNDEFINED)
            break;
        for (int k = 0; k < count; ++k) {
            try {
                onCompleted(static_cast<std::size_t>(done[static_cast<std::size_t>(k)]));
            } catch (...) { // a corrupt size: nothing to receive for it
            }
        }
    }
    MPI_Waitall(static_cast<int>(m_sendRequests.size()), m_sendRequests.data(),
                MPI_STATUSES_IGNORE);
    m_sendRequests.clear();
    for (auto& b : m_send)
        b.clear();
    m_inFlight = false;
}

} // namespace regolith::core
