#include "io/checkpoint/GrainState.hpp"

#include <cstring>

namespace regolith::io {

std::vector<GrainState> collectMasters(particles::LocalParticles const& local) {
    std::vector<GrainState> out;
    out.reserve(local.countMasters());
    for (particles::BlockParticles const& bp : local.blocks()) {
        particles::ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            GrainState g;
            g.uid = ps.uid(i);
            g.position = ps.position(i);
            g.velocity = ps.velocity(i);
            g.angularVelocity = ps.angularVelocity(i);
            g.orientation = ps.orientation(i);
            g.force = ps.force(i);
            g.torque = ps.torque(i);
            g.radius = ps.radius(i);
            g.mass = ps.mass(i);
            g.type = ps.type(i);
            g.flags = ps.flags(i).bits();
            g.history.assign(ps.history(i).begin(), ps.history(i).end());
            g.fields = ps.fieldValues(i);
            out.push_back(std::move(g));
        });
    }
    return out;
}

particles::ParticleInit toParticleInit(GrainState const& g) {
    particles::ParticleInit p;
    p.uid = g.uid;
    p.position = g.position;
    p.velocity = g.velocity;
    p.angularVelocity = g.angularVelocity;
    p.orientation = g.orientation;
    p.radius = g.radius;
    p.mass = g.mass;
    p.type = g.type;
    // Every stored flag as written; a restored grain is a master.
    p.flags = particles::Flags::fromBits(g.flags).set(particles::Flag::Shadow, false);
    p.fields = g.fields;
    return p;
}

void restoreDynamicState(GrainState const& g, particles::ParticleStorage& ps,
                         particles::ParticleStorage::Index i) {
    ps.force(i) = g.force;
    ps.torque(i) = g.torque;
    ps.history(i).clear();
    for (particles::HistoryEntry const& e : g.history)
        ps.history(i).set(e);
}

std::uint64_t fnv1a(std::span<std::byte const> bytes, std::uint64_t seed) {
    std::uint64_t h = seed;
    for (std::byte b : bytes) {
        h ^= static_cast<std::uint64_t>(b);
        h *= 0x100000001B3ULL;
    }
    return h;
}

namespace {

/// Feeds values to FNV-1a; doubles by their bit pattern (so -0.0 and 0.0 differ, as they
/// should for a bitwise restart).
class Hasher {
public:
    template <class T>
    void add(T const& v) {
        m_h = fnv1a(std::as_bytes(std::span<T const, 1>(&v, 1)), m_h);
    }
    void add(core::Vec3 const& v) {
        for (int k = 0; k < 3; ++k)
            add(v[k]);
    }
    [[nodiscard]] std::uint64_t value() const { return m_h; }

private:
    std::uint64_t m_h = 0xCBF29CE484222325ULL;
};

std::uint64_t fmix64(std::uint64_t k) {
    k ^= k >> 33U;
    k *= 0xFF51AFD7ED558CCDULL;
    k ^= k >> 33U;
    k *= 0xC4CEB9FE1A85EC53ULL;
    k ^= k >> 33U;
    return k;
}

} // namespace

std::uint64_t grainHash(GrainState const& g) {
    Hasher h;
    h.add(g.uid);
    h.add(g.position);
    h.add(g.velocity);
    h.add(g.angularVelocity);
    h.add(g.orientation.w());
    h.add(g.orientation.x());
    h.add(g.orientation.y());
    h.add(g.orientation.z());
    h.add(g.force);
    h.add(g.torque);
    h.add(g.radius);
    h.add(g.mass);
    h.add(g.type);
    h.add(g.flags);
    h.add(g.gravityReference);
    h.add(g.gravityField);
    h.add(g.gravitySlope);
    for (particles::HistoryEntry const& e : g.history) {
        h.add(e.partner);
        h.add(e.spring);
        h.add(e.stamp);
    }
    for (double v : g.fields)
        h.add(v);
    return fmix64(h.value());
}

} // namespace regolith::io
