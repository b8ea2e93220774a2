#include "apps/common/StateChecksum.hpp"

#include <array>

namespace regolith::apps {

namespace {

/// MurmurHash3's fmix64 (Austin Appleby, public domain, smhasher/src/MurmurHash3.cpp).
std::uint64_t fmix64(std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    k *= 0xc4ceb9fe1a85ec53ULL;
    k ^= k >> 33;
    return k;
}

void addVec3(StateChecksum& h, core::Vec3 const& v) {
    h.add(v.x());
    h.add(v.y());
    h.add(v.z());
}

} // namespace

std::uint64_t masterDigest(MasterRecord const& m) {
    StateChecksum h;
    h.add(m.uid);
    addVec3(h, m.position);
    addVec3(h, m.velocity);
    addVec3(h, m.angularVelocity);
    h.add(m.radius);
    h.add(m.mass);
    return fmix64(h.value());
}

std::string stateChecksum(core::Comm const& comm, std::span<MasterRecord const> local) {
    return stateChecksumFrom(comm, sourceOf(local));
}

std::string stateChecksumFrom(core::Comm const& comm, MasterSource const& local) {
    // [count, sum of digests]; unsigned addition wraps modulo 2^64, in MPI_SUM as in C++.
    std::array<std::uint64_t, 2> totals{0, 0};
    local([&](MasterRecord const& m) {
        ++totals[0];
        totals[1] += masterDigest(m);
    });
    comm.allReduceInPlace(std::span<std::uint64_t>(totals), core::ReduceOp::Sum);
    StateChecksum digest;
    digest.add(totals[0]);
    digest.add(totals[1]);
    return digest.hex();
}

} // namespace regolith::apps
