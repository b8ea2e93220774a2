#include "apps/common/StateDump.hpp"

#include "core/Error.hpp"
#include "core/mpi/Buffer.hpp"
#include "particles/storage/GrainFields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

namespace regolith::apps {

namespace {

using particles::GrainLayoutOf;
using particles::kGrainQuantity;

template <std::size_t K>
constexpr bool kInDump = particles::grainWrittenTo<K>(particles::kDump);

/// A record's bytes in a gathered message: the table's dump columns, then the grain fields.
std::size_t recordBytes() {
    std::size_t bytes = 0;
    particles::forEachGrainQuantity([&](auto k) {
        if constexpr (kInDump<k.value>)
            bytes += kGrainQuantity<k.value>.components *
                     sizeof(typename GrainLayoutOf<k.value>::Element);
    });
    return bytes + particles::grainFieldComponents() * sizeof(double);
}

std::string pack(std::span<MasterRecord const> masters) {
    core::SendBuffer b;
    b.reserve(masters.size() * recordBytes());
    std::size_t const fields = particles::grainFieldComponents();
    for (auto const& m : masters) {
        particles::forEachGrainQuantity([&](auto k) {
            if constexpr (kInDump<k.value>)
                b << m.*kGrainQuantity<k.value>.row;
        });
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
        particles::forEachGrainQuantity([&](auto k) {
            if constexpr (kInDump<k.value>)
                b >> m.*kGrainQuantity<k.value>.row;
        });
        m.fields.resize(particles::grainFieldComponents());
        for (double& v : m.fields)
            b >> v;
        out.push_back(std::move(m));
    }
}

} // namespace

std::string dumpHeader() {
    std::string header;
    particles::forEachGrainQuantity([&](auto k) {
        if constexpr (kInDump<k.value>) {
            if (!header.empty())
                header += ',';
            header += kGrainQuantity<k.value>.dumpColumns;
        }
    });
    for (particles::GrainField const& f : particles::grainFields()) {
        header += ',';
        if (f.components == 1)
            header += f.name;
        else
            header += fmt::format("{0}_x,{0}_y,{0}_z", f.name);
    }
    return header + "\n";
}

std::string dumpCsv(std::span<MasterRecord const> masters) {
    std::vector<MasterRecord const*> order;
    order.reserve(masters.size());
    for (auto const& m : masters)
        order.push_back(&m);
    std::sort(order.begin(), order.end(),
              [](MasterRecord const* a, MasterRecord const* b) { return a->uid < b->uid; });
    fmt::memory_buffer out;
    auto text = std::back_inserter(out);
    fmt::format_to(text, "{}", dumpHeader());
    for (MasterRecord const* m : order) {
        char const* separator = "";
        particles::forEachGrainQuantity([&](auto k) {
            if constexpr (kInDump<k.value>) {
                using Element = typename GrainLayoutOf<k.value>::Element;
                std::array<Element, kGrainQuantity<k.value>.components> e{};
                GrainLayoutOf<k.value>::put(m->*kGrainQuantity<k.value>.row, e.data());
                for (Element x : e) {
                    if constexpr (std::is_floating_point_v<Element>)
                        fmt::format_to(text, "{}{:.17g}", separator, x);
                    else
                        fmt::format_to(text, "{}{}", separator, x);
                    separator = ",";
                }
            }
        });
        for (double value : m->fields)
            fmt::format_to(text, ",{:.17g}", value);
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
