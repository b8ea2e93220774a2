#include "apps/common/StateDump.hpp"

#include "core/Error.hpp"
#include "core/mpi/Buffer.hpp"
#include "particles/storage/GrainFields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

namespace regolith::apps {

namespace {

/// A record's bytes in a gathered message: the contract's columns, then the grain fields.
std::size_t recordBytes() {
    return sizeof(std::uint64_t) + (11 + particles::grainFieldComponents()) * sizeof(double);
}

std::string pack(std::span<MasterRecord const> masters) {
    core::SendBuffer b;
    b.reserve(masters.size() * recordBytes());
    std::size_t const fields = particles::grainFieldComponents();
    for (auto const& m : masters) {
        b << m.uid << m.position << m.velocity << m.angularVelocity << m.radius << m.mass;
        for (std::size_t k = 0; k < fields; ++k)
            b << (k < m.fields.size() ? m.fields[k] : 0.0);
    }
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
        m.fields.resize(particles::grainFieldComponents());
        for (double& v : m.fields)
            b >> v;
        out.push_back(std::move(m));
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
    out.append(kDumpHeader.substr(0, kDumpHeader.size() - 1));
    for (particles::GrainField const& f : particles::grainFields()) {
        if (f.components == 1)
            fmt::format_to(std::back_inserter(out), ",{}", f.name);
        else
            fmt::format_to(std::back_inserter(out), ",{0}_x,{0}_y,{0}_z", f.name);
    }
    out.push_back('\n');
    for (MasterRecord const* m : order) {
        auto const& x = m->position;
        auto const& v = m->velocity;
        auto const& w = m->angularVelocity;
        fmt::format_to(std::back_inserter(out),
                       "{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                       "{:.17g},{:.17g}",
                       m->uid, x.x(), x.y(), x.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z(),
                       m->radius, m->mass);
        for (double value : m->fields)
            fmt::format_to(std::back_inserter(out), ",{:.17g}", value);
        out.push_back('\n');
    }
    return fmt::to_string(out);
}

std::string gatherDumpCsv(core::Comm const& comm, std::span<MasterRecord const> local) {
    std::size_t const bytesPerRecord = recordBytes();
    auto const total = comm.allReduce(static_cast<unsigned long>(local.size() * bytesPerRecord),
                                      core::ReduceOp::Sum);
    if (total > static_cast<unsigned long>(std::numeric_limits<int>::max()))
        throw core::InputError(fmt::format("--dump: the state ({} masters) is too large to gather "
                                           "on one rank (at most {} masters)",
                                           total / bytesPerRecord,
                                           std::numeric_limits<int>::max() / bytesPerRecord));
    auto const parts = comm.gatherStrings(pack(local), 0);
    if (comm.rank() != 0)
        return {};
    std::vector<MasterRecord> all;
    all.reserve(total / bytesPerRecord);
    for (auto const& part : parts)
        unpack(part, all);
    return dumpCsv(all);
}

} // namespace regolith::apps
