#pragma once
/// The passes over every copy of a block that the per-step synchronisation makes before its
/// per-grain work. They pick out the few copies that work concerns (masters near a face,
/// shadows) from the many it does not (masters deep inside their block), reading the block's
/// arrays in order and without a branch per grain: a pass costs a few instructions per grain,
/// where the per-grain code costs hundreds for the copies it visits.
#include "particles/storage/ParticleFlags.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/SyncEngine.hpp"

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace regolith::particles::sync_detail {

/// Calls f(i), ascending, for every i whose flags hold every bit of `kMask`. The flag bytes are
/// read eight at a time: a word in which no byte holds them all is skipped in a few
/// instructions (most copies of a scene are masters, or NNS-class).
template <std::uint8_t kMask, class F>
void forEachWithFlags(std::vector<Flags> const& flags, F&& f) {
    static_assert(sizeof(Flags) == 1 && kMask != 0);
    constexpr std::uint64_t kLowBits = 0x0101010101010101ULL;
    std::size_t const n = flags.size();
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        std::uint64_t w = 0;
        std::memcpy(&w, &flags[i], 8);
        // Bit 0 of byte j of `all` is the AND of byte j's mask bits: w >> b brings bit b of
        // byte j to its bit 0 (bits shifted in from byte j + 1 land above bit 0, and kLowBits
        // drops them).
        std::uint64_t all = ~std::uint64_t{0};
        for (unsigned b = 0; b < 8; ++b)
            if ((kMask >> b) & 1U)
                all &= w >> b;
        if ((all & kLowBits) == 0)
            continue;
        for (std::size_t j = i; j < i + 8; ++j)
            if ((flags[j].bits() & kMask) == kMask)
                f(j);
    }
    for (; i < n; ++i)
        if ((flags[i].bits() & kMask) == kMask)
            f(i);
}

/// What the first pass of ParticleSync::sync found in one block.
struct MasterScan {
    /// Ascending indices of the masters the call must process (Alg. 1 / 2 per grain): all but
    /// the settled ones -- small (radius below the smallest edge around the block), without
    /// shadow holders, deep inside the block (ParticleSync::Impl::deepInside), and with
    /// Flag::Spreads already as the method wants it. For those Alg. 1 and 2 find no target and
    /// change nothing.
    std::span<std::uint32_t const> visit; ///< 4-byte indices: the scratch spans every copy
    /// Whether some shadow of the block is SOS-class (Flag::Spreads): round 2 has work.
    bool spreadingShadows = false;
};

/// The first pass over block `bp`; `spreads` is the Flag::Spreads of a settled master (true
/// for SOS, false for NNS and hybrid); radii are grown by `grow` (SyncConfig::skin). `visit`
/// points into `scratch`, valid until its next use. Local.
MasterScan scanMasters(ParticleSync::Impl const& engine, BlockParticles const& bp, bool spreads,
                       double grow, std::vector<std::uint32_t>& scratch);

} // namespace regolith::particles::sync_detail
