#include "core/mpi/SparseExchange.hpp"

#include "core/Error.hpp"
#include "core/mpi/Requests.hpp"
#include "core/mpi/Tags.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>

namespace regolith::core {

namespace {

/// Error word of a call without error; otherwise sender * size + destination (lowest wins).
constexpr std::int64_t kNoError = std::numeric_limits<std::int64_t>::max();

} // namespace

SparseExchange::SparseExchange(Comm const& comm, std::uint64_t maxMessageBytes)
    : m_comm(comm.duplicate())
    , m_maxMessageBytes(maxMessageBytes) {
    // Agreed on by all ranks, so every rank throws the same error or none does.
    auto const limit = static_cast<std::int64_t>(
        std::min<std::uint64_t>(maxMessageBytes, std::numeric_limits<std::int64_t>::max()));
    std::array<std::int64_t, 2> range{limit, -limit};
    m_comm.allReduceInPlace(std::span<std::int64_t>(range), ReduceOp::Min);
    if (range[0] != -range[1])
        throw Error(fmt::format("SparseExchange: maxMessageBytes differs between ranks ({} to {})",
                                range[0], -range[1]));
    if (range[0] < 1 || static_cast<std::uint64_t>(range[0]) > kMaxMessageBytes)
        throw Error(fmt::format("SparseExchange: maxMessageBytes {} not in [1, {}]", range[0],
                                kMaxMessageBytes));
}

SparseExchange::~SparseExchange() {
    if (inFlight())
        completeDiscarding();
}

int SparseExchange::currentTag() const {
    // m_call counts started calls, so the call in flight is number m_call - 1.
    return toInt((m_call - 1) % 2 == 0 ? Tag::SparseExchange : Tag::SparseExchangeAlt);
}

void SparseExchange::requireUsable() const {
    if (!m_mpiError.empty())
        throw Error("SparseExchange unusable after an MPI error: " + m_mpiError);
}

void SparseExchange::mpiCheck(int mpiResult, char const* what) {
    if (mpiResult == MPI_SUCCESS)
        return;
    try {
        Comm::check(mpiResult, what);
    } catch (Error const& e) {
        abandon(e.what());
        throw;
    }
}

void SparseExchange::abandon(std::string const& why) noexcept {
    releaseSends(m_sendRequests);
    m_sendRequests.clear();
    // A nonblocking collective may be neither freed nor cancelled (MPI-3.1 §5.12); after an
    // MPI error it may never complete either. The handle is dropped, the object unusable.
    m_closing = MPI_REQUEST_NULL;
    m_received.clear();
    m_phase = Phase::Idle;
    try {
        m_mpiError = why;
    } catch (...) { // out of memory for the text: still mark the object unusable
        m_mpiError.clear();
        m_mpiError.push_back('?');
    }
}

SendBuffer& SparseExchange::sendBuffer(int dest) {
    requireUsable();
    if (inFlight())
        throw Error("SparseExchange::sendBuffer called between start() and wait()");
    if (dest < 0 || dest >= m_comm.size())
        throw Error(fmt::format("SparseExchange: destination rank {} out of range [0, {})", dest,
                                m_comm.size()));
    return m_send[dest];
}

void SparseExchange::start() {
    requireUsable();
    if (inFlight())
        throw Error("SparseExchange::start called twice without wait()");
    int const me = m_comm.rank();
    // Everything that allocates happens before the first send, so that afterwards only an
    // MPI error can throw (and mpiCheck() then gives up on what was posted).
    m_received.clear();
    m_sendRequests.clear();
    m_sendRequests.reserve(m_send.size());
    if (auto self = m_send.find(me); self != m_send.end())
        m_received.push_back(Message{me, RecvBuffer(self->second.release())});

    ++m_call;
    int const tag = currentTag();
    m_local = {kNoError, 0};
    CommStats stats;
    for (auto& [dest, buffer] : m_send) {
        if (dest == me)
            continue;
        if (buffer.size() > m_maxMessageBytes) { // not sent; every rank learns of it in wait()
            m_local[0] = std::min(m_local[0], std::int64_t{me} * m_comm.size() + dest);
            continue;
        }
        // Synchronous mode: completion means the receiver has matched the message, which is
        // what lets a rank enter the reduction knowing its messages are out of the network.
        mpiCheck(MPI_Issend(buffer.data(), static_cast<int>(buffer.size()), MPI_BYTE, dest, tag,
                            m_comm.raw(), &m_sendRequests.emplace_back()),
                 "MPI_Issend");
        stats.messages += 1;
        stats.bytes += buffer.size();
        ++stats.peers;
    }
    m_counters.record(stats);
    m_phase = Phase::Sending;
}

void SparseExchange::progress() {
    if (m_comm.size() == 1) {
        // No other rank: nothing to probe for, no send to match, and the reduction over one
        // rank is the identity (every one-rank synchronisation calls this).
        m_global = m_local;
        m_phase = Phase::Idle;
    }
    int const tag = currentTag();
    MPI_Comm const raw = m_comm.raw();
    while (m_phase != Phase::Idle) {
        // Receive whatever has arrived. Iprobe does not match the message, so if allocating
        // its buffer throws, it is still there when the call is resumed.
        int arrived = 0;
        MPI_Status status;
        mpiCheck(MPI_Iprobe(MPI_ANY_SOURCE, tag, raw, &arrived, &status), "MPI_Iprobe");
        if (arrived) {
            int count = 0;
            mpiCheck(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
            std::vector<std::byte> data(static_cast<std::size_t>(count));
            if (m_received.size() == m_received.capacity()) // push_back below cannot throw
                m_received.reserve(std::max<std::size_t>(8, 2 * m_received.capacity()));
            // The first message from this source with this tag is the probed one (MPI's
            // non-overtaking rule); a later call's message would carry the other tag.
            mpiCheck(MPI_Recv(data.data(), count, MPI_BYTE, status.MPI_SOURCE, tag, raw,
                              MPI_STATUS_IGNORE),
                     "MPI_Recv");
            m_received.push_back(Message{status.MPI_SOURCE, RecvBuffer(std::move(data))});
            continue; // drain what is there before testing for completion
        }
        if (m_phase == Phase::Sending) {
            int sent = 0;
            mpiCheck(MPI_Testall(static_cast<int>(m_sendRequests.size()), m_sendRequests.data(),
                                 &sent, MPI_STATUSES_IGNORE),
                     "MPI_Testall");
            if (sent) {
                m_sendRequests.clear();
                mpiCheck(MPI_Iallreduce(m_local.data(), m_global.data(), 2, MPI_INT64_T, MPI_MIN,
                                        raw, &m_closing),
                         "MPI_Iallreduce");
                m_phase = Phase::Closing;
            }
        } else {
            int done = 0;
            mpiCheck(MPI_Test(&m_closing, &done, MPI_STATUS_IGNORE), "MPI_Test");
            if (done)
                m_phase = Phase::Idle;
        }
    }
    m_send.clear();
}

void SparseExchange::completeDiscarding() noexcept {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (finalised) { // the handles died with MPI
        m_sendRequests.clear();
        m_closing = MPI_REQUEST_NULL;
        m_phase = Phase::Idle;
        return;
    }
    m_received.clear();
    m_received.shrink_to_fit(); // give the memory back before receiving on
    try {
        progress();
    } catch (Error const&) { // an MPI error: mpiCheck() has given up already
    } catch (...) {          // out of memory again: nothing more can be done here
        abandon("out of memory while completing a call");
    }
    m_received.clear();
    m_send.clear();
}

void SparseExchange::raiseFlag() {
    if (m_phase != Phase::Sending)
        throw Error("SparseExchange::raiseFlag called without a call in flight");
    m_local[1] = -1;
}

std::vector<SparseExchange::Message> SparseExchange::wait() {
    requireUsable();
    if (!inFlight())
        throw Error("SparseExchange::wait called without start()");
    try {
        progress();
    } catch (...) {
        if (inFlight()) // not an MPI error: the other ranks still need this rank in the call
            completeDiscarding();
        throw;
    }
    std::vector<Message> received = std::move(m_received);
    m_received.clear();
    if (m_global[0] != kNoError) {
        int const p = m_comm.size();
        throw Error(fmt::format("SparseExchange: rank {} has a message for rank {} larger than "
                                "the limit of {} bytes",
                                m_global[0] / p, m_global[0] % p, m_maxMessageBytes));
    }
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
