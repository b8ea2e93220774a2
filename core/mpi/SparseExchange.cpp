#include "core/mpi/SparseExchange.hpp"

#include "core/Error.hpp"
#include "core/mpi/Tags.hpp"

#include <climits>
#include <fmt/format.h>

#include <algorithm>

namespace regolith::core {

namespace {

constexpr std::size_t kMaxMessageBytes = INT_MAX; // MPI counts are int (no MPI-4 "_c" calls)

} // namespace

SparseExchange::SparseExchange(Comm const& comm)
    : m_comm(comm.duplicate()) {}

SparseExchange::~SparseExchange() {
    if (!m_inFlight)
        return;
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (finalised)
        return;
    try {
        static_cast<void>(wait());
    } catch (...) { // nothing sensible left to do in a destructor
    }
}

int SparseExchange::currentTag() const {
    // m_call counts started calls, so the call in flight is number m_call - 1.
    return toInt((m_call - 1) % 2 == 0 ? Tag::SparseExchange : Tag::SparseExchangeAlt);
}

SendBuffer& SparseExchange::sendBuffer(int dest) {
    if (m_inFlight)
        throw Error("SparseExchange::sendBuffer called between start() and wait()");
    if (dest < 0 || dest >= m_comm.size())
        throw Error(fmt::format("SparseExchange: destination rank {} out of range [0, {})", dest,
                                m_comm.size()));
    return m_send[dest];
}

void SparseExchange::start() {
    if (m_inFlight)
        throw Error("SparseExchange::start called twice without wait()");
    for (auto const& [dest, buffer] : m_send)
        if (buffer.size() > kMaxMessageBytes)
            throw Error(fmt::format("SparseExchange: {}-byte message to rank {} exceeds the MPI "
                                    "limit of {} bytes",
                                    buffer.size(), dest, kMaxMessageBytes));
    ++m_call;
    int const tag = currentTag();
    m_sendRequests.clear();
    m_self.clear();
    CommStats stats;
    for (auto& [dest, buffer] : m_send) {
        if (dest == m_comm.rank()) {
            m_self.push_back(Message{dest, RecvBuffer(buffer.release())});
            continue;
        }
        // Synchronous mode: completion means the receiver has matched the message, which is
        // what lets a rank enter the barrier knowing its messages are out of the network.
        Comm::check(MPI_Issend(buffer.data(), static_cast<int>(buffer.size()), MPI_BYTE, dest, tag,
                               m_comm.raw(), &m_sendRequests.emplace_back()),
                    "MPI_Issend");
        stats.messages += 1;
        stats.bytes += buffer.size();
        ++stats.peers;
    }
    m_counters.record(stats);
    m_inFlight = true;
}

std::vector<SparseExchange::Message> SparseExchange::wait() {
    if (!m_inFlight)
        throw Error("SparseExchange::wait called without start()");
    int const tag = currentTag();
    MPI_Comm const raw = m_comm.raw();
    std::vector<Message> received = std::move(m_self);
    m_self.clear();

    MPI_Request barrier = MPI_REQUEST_NULL;
    bool inBarrier = false;
    for (;;) {
        // Receive whatever has arrived (matched probe: safe even if threads probed too).
        int arrived = 0;
        MPI_Message handle = MPI_MESSAGE_NULL;
        MPI_Status status;
        Comm::check(MPI_Improbe(MPI_ANY_SOURCE, tag, raw, &arrived, &handle, &status),
                    "MPI_Improbe");
        if (arrived) {
            int count = 0;
            Comm::check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
            std::vector<std::byte> data(static_cast<std::size_t>(count));
            Comm::check(MPI_Mrecv(data.data(), count, MPI_BYTE, &handle, MPI_STATUS_IGNORE),
                        "MPI_Mrecv");
            received.push_back(Message{status.MPI_SOURCE, RecvBuffer(std::move(data))});
            continue; // drain what is there before testing for completion
        }
        if (!inBarrier) {
            int sent = 0;
            Comm::check(MPI_Testall(static_cast<int>(m_sendRequests.size()), m_sendRequests.data(),
                                    &sent, MPI_STATUSES_IGNORE),
                        "MPI_Testall");
            if (sent) {
                Comm::check(MPI_Ibarrier(raw, &barrier), "MPI_Ibarrier");
                inBarrier = true;
            }
        } else {
            int done = 0;
            Comm::check(MPI_Test(&barrier, &done, MPI_STATUS_IGNORE), "MPI_Test");
            if (done)
                break;
        }
    }
    m_send.clear();
    m_sendRequests.clear();
    m_inFlight = false;

    // Arrival order is a race; delivery order must not be. One message per source and call.
    std::sort(received.begin(), received.end(),
              [](Message const& a, Message const& b) { return a.rank < b.rank; });
    for (std::size_t i = 1; i < received.size(); ++i)
        if (received[i - 1].rank == received[i].rank)
            throw Error(fmt::format("SparseExchange: two messages from rank {} in one call",
                                    received[i].rank));
    return received;
}

} // namespace regolith::core
