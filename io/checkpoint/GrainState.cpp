#include "io/checkpoint/GrainState.hpp"

#include <array>
#include <cstring>

namespace regolith::io {

std::vector<GrainState> collectMasters(particles::LocalParticles const& local) {
    std::vector<GrainState> out;
    out.reserve(local.countMasters());
    for (particles::BlockParticles const& bp : local.blocks()) {
        particles::ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            GrainState g;
            static_cast<particles::GrainRow&>(g) = ps.row(i);
            g.history.assign(ps.history(i).begin(), ps.history(i).end());
            g.fields = ps.fieldValues(i);
            out.push_back(std::move(g));
        });
    }
    return out;
}

particles::ParticleInit toParticleInit(GrainState const& g) {
    particles::ParticleInit p;
    static_cast<particles::GrainRow&>(p) = g;
    // Every stored flag as written; a restored grain is a master.
    p.flags.set(particles::Flag::Shadow, false);
    p.fields = g.fields;
    return p;
}

void restoreHistory(GrainState const& g, particles::ParticleStorage& ps,
                    particles::ParticleStorage::Index i) {
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
    /// A table entry's value by its column elements (a quaternion as w, x, y, z; flags as
    /// their byte).
    template <class T>
    void addValue(T const& v) {
        using Layout = particles::GrainValueLayout<T>;
        std::array<typename Layout::Element, Layout::components> e{};
        Layout::put(v, e.data());
        for (auto const& x : e)
            add(x);
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
    particles::forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = particles::kGrainQuantity<k.value>;
        if constexpr ((q.outputs & particles::kCheckpoint) != 0)
            h.addValue(g.*q.row);
    });
    for (particles::HistoryEntry const& e : g.history) {
        h.add(e.partner);
        h.addValue(e.spring);
        h.add(e.stamp);
    }
    for (double v : g.fields)
        h.add(v);
    return fmix64(h.value());
}

} // namespace regolith::io
