#include "apps/spin_up/PileRecords.hpp"

#include "apps/regolith/LoopSummary.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>

namespace regolith::apps {

namespace {

/// A record's values as they travel: uid (its bits), position, velocity, angular velocity,
/// radius, mass.
constexpr std::size_t kValues = 12;

void pack(MasterRecord const& m, double* out) {
    out[0] = std::bit_cast<double>(m.uid);
    for (int d = 0; d < 3; ++d) {
        out[1 + d] = m.position[d];
        out[4 + d] = m.velocity[d];
        out[7 + d] = m.angularVelocity[d];
    }
    out[10] = m.radius;
    out[11] = m.mass;
}

MasterRecord unpack(double const* in) {
    MasterRecord m;
    m.uid = std::bit_cast<std::uint64_t>(in[0]);
    m.position = core::Vec3(in[1], in[2], in[3]);
    m.velocity = core::Vec3(in[4], in[5], in[6]);
    m.angularVelocity = core::Vec3(in[7], in[8], in[9]);
    m.radius = in[10];
    m.mass = in[11];
    return m;
}

} // namespace

std::vector<MasterRecord> gatherMastersByUid(core::Comm const& comm,
                                             particles::LocalParticles const& local) {
    std::vector<MasterRecord> const mine = masterRecords(local);
    std::vector<double> values(mine.size() * kValues);
    for (std::size_t i = 0; i < mine.size(); ++i)
        pack(mine[i], values.data() + i * kValues);
    std::vector<double> const all = comm.allGatherVarying<double>(std::span<double const>(values));
    std::vector<MasterRecord> out;
    out.reserve(all.size() / kValues);
    for (std::size_t i = 0; i < all.size(); i += kValues)
        out.push_back(unpack(all.data() + i));
    std::sort(out.begin(), out.end(),
              [](MasterRecord const& a, MasterRecord const& b) { return a.uid < b.uid; });
    return out;
}

} // namespace regolith::apps
