#pragma once
/// The kept springs carried from one Verlet list to the next (ContactDetector's class comment,
/// "Springs kept beside the list"): at a rebuild the live springs are set aside by the storage
/// index of their pair's canonical i (a counting sort) instead of going back to the grains'
/// histories, and each kept pair of the new list takes its partner's from i's run, one
/// contiguous read. ContactDetector writes back those no new pair takes (SpringCarry.cpp).
#include "particles/detection/VerletList.hpp"
#include "particles/storage/ContactHistory.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

class CarriedSprings {
public:
    /// A spring set aside: its partner's storage index, history slot hint and value.
    struct Spring {
        std::uint32_t partner;
        std::uint8_t hint;
        KeptSpring spring;
    };

    /// Sets aside the springs of `list`'s kept pairs that were touched since their fill (an
    /// untouched one would not be written back), by i; `copies` bounds the storage indices.
    void setAside(VerletList const& list, std::size_t copies);
    [[nodiscard]] bool empty() const { return m_springs.empty(); }
    /// The spring set aside for the pair (i, j), marked taken; nullptr if there is none.
    [[nodiscard]] Spring const* take(std::size_t i, std::size_t j);
    /// Calls f(i, spring) for every spring no pair took, then forgets them all.
    template <class F>
    void drain(F&& f) {
        if (m_springs.empty())
            return; // (m_start may be an earlier rebuild's)
        for (std::size_t i = 0; i + 1 < m_start.size(); ++i)
            for (std::uint32_t k = m_start[i]; k < m_start[i + 1]; ++k)
                if (m_springs[k].partner != kTaken)
                    f(i, m_springs[k]);
        m_springs.clear();
    }
    [[nodiscard]] std::size_t bytes() const;

private:
    static constexpr std::uint32_t kTaken = 0xffffffffu; ///< a taken spring's partner
    std::vector<Spring> m_springs;                       ///< by i
    std::vector<std::uint32_t> m_start;  ///< per storage index + 1: where i's springs start
    std::vector<std::uint32_t> m_cursor; ///< the counting sort's cursors
};

} // namespace regolith::particles
