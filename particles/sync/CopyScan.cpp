#include "particles/sync/CopyScan.hpp"

#include "core/memory/GentleGrowth.hpp"

namespace regolith::particles::sync_detail {

MasterScan scanMasters(ParticleSync::Impl const& engine, BlockParticles const& bp, bool spreads,
                       double grow, std::vector<std::uint32_t>& scratch) {
    ParticleStorage const& ps = bp.particles;
    std::uint64_t const id = bp.block->id.raw();
    double const edge = engine.edgeAround(id);
    ParticleSync::Impl::DeepTest const deep = engine.deepTest(id);
    std::size_t const n = ps.size();
    if (scratch.size() < n) {       // grown, never shrunk: no per-call initialisation
        if (scratch.capacity() < n) // by a sixteenth: resize's doubling is 4 B per copy more
            scratch.reserve(core::gentleCapacity(n));
        scratch.resize(n);
    }
    if (n == 0)
        return {};
    // Raw pointers and a local copy of the test: nothing the loop stores (indices) can then
    // be taken to change them, so they stay in registers.
    core::Vec3 const* x = ps.positions().data();
    double const* r = ps.radii().data();
    Flags const* flags = ps.allFlags().data();
    HolderList const* holders = &ps.shadowHolders(0);
    std::uint32_t* out = scratch.data();
    std::size_t count = 0;
    bool spreadingShadow = false;
    for (std::size_t i = 0; i < n; ++i) {
        Flags const f = flags[i];
        bool const shadow = f.isShadow();
        bool const flagged = f.has(Flag::Spreads);
        spreadingShadow = spreadingShadow | (shadow & flagged);
        double const reach = r[i] + grow;
        bool const settled = (reach < edge) & holders[i].empty() & (flagged == spreads) &
                             engine.deepInside(deep, x[i], reach);
        out[count] = static_cast<std::uint32_t>(i); // kept only if counted: no branch on it
        count += static_cast<std::size_t>(!(shadow | settled));
    }
    return {std::span<std::uint32_t const>(out, count), spreadingShadow};
}

} // namespace regolith::particles::sync_detail
