#include "apps/common/StateDump.hpp"

#include "core/Error.hpp"
#include "core/mpi/Buffer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

namespace regolith::apps {

namespace {

constexpr std::size_t kRecordBytes = sizeof(std::uint64_t) + 11 * sizeof(double);

std::string pack(std::span<MasterRecord const> masters) {
    core::SendBuffer b;
    b.reserve(masters.size() * kRecordBytes);
    for (auto const& m : masters)
        b << m.uid << m.position << m.velocity << m.angularVelocity << m.radius << m.mass;
    auto const bytes = b.bytes();
    return {reinterpret_cast<char const*>(bytes.data()), bytes.size()};
}

void unpack(std::string const& text, std::vector<MasterRecord>& out) {
    std::vector<std::byte> bytes(text.size());
    std::copy(text.begin(), text.end(), reinterpret_cast<char*>(bytes.data()));
    core::RecvBuffer b(std::move(bytes));
    while (!b.exhausted()) {
        MasterRecord m;
        b >> m.uid >> m.position >> m.velocity >> m.angularVelocity >> m.radius >> m.mass;
        out.push_back(m);
    }
}

} // namespace

std::string dumpCsv(std::span<MasterRecord const> masters) {
    std::vector<MasterRecord const*> order;
    order.reserve(masters.size());
    for (auto const& m : masters)
        order.push_back(&m);
    std::sort(order.begin(), order.end(),
              [](MasterRecord const* a, MasterRecord const* b) { return a->uid < b->uid; });
    fmt::memory_buffer out;
    out.append(kDumpHeader);
    for (MasterRecord const* m : order) {
        auto const& x = m->position;
        auto const& v = m->velocity;
        auto const& w = m->angularVelocity;
        fmt::format_to(std::back_inserter(out),
                       "{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                       "{:.17g},{:.17g}\n",
                       m->uid, x.x(), x.y(), x.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z(),
                       m->radius, m->mass);
    }
    return fmt::to_string(out);
}

std::string gatherDumpCsv(core::Comm const& comm, std::span<MasterRecord const> local) {
    auto const total = comm.allReduce(static_cast<unsigned long>(local.size() * kRecordBytes),
                                      core::ReduceOp::Sum);
    if (total > static_cast<unsigned long>(std::numeric_limits<int>::max()))
        throw core::InputError(fmt::format("--dump: the state ({} masters) is too large to gather "
                                           "on one rank (at most {} masters)",
                                           total / kRecordBytes,
                                           std::numeric_limits<int>::max() / kRecordBytes));
    auto const parts = comm.gatherStrings(pack(local), 0);
    if (comm.rank() != 0)
        return {};
    std::vector<MasterRecord> all;
    all.reserve(total / kRecordBytes);
    for (auto const& part : parts)
        unpack(part, all);
    return dumpCsv(all);
}

} // namespace regolith::apps
