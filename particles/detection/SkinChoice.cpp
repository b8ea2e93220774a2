// ContactDetector's choice of the Verlet list's skin for the scene
// (DetectorConfig::widestRelativeSkin). A list that must be rebuilt every few steps (a packing
// that flows as a whole) costs its rebuilds, which a wider skin makes rarer; in a gas a wider
// skin lists many more pairs, each tested every step. So every 16th rebuild (the first
// included) bins with the widest skin, counts the pairs each candidate skin (1, 2, ... times
// relativeSkin) would list, and takes the widest that lists at most an eighth more pairs than
// relativeSkin; the rebuilds until the next choice use it. In a packing of equal spheres the
// next shell lies 0.41 diameters beyond the first, so the list of the first shell takes a skin
// of up to 0.4 diameters at no cost per step (the ramp of the first paper's scene B: half the
// rebuilds). The list holds the pairs of any skin's list: the contacts do not depend on it. The
// order in which their forces are summed does (the list's rebuilds and arrivals order its
// pairs), and with it the trajectory's last bits, except in reproducible mode.
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::particles {

bool ContactDetector::widens() const {
    return m_config.skin == 0.0 && m_config.relativeSkin > 0.0 &&
           m_config.widestRelativeSkin > m_config.relativeSkin;
}

double ContactDetector::chooseRelativeSkin(ParticleStorage const& ps,
                                           LocalPositions const& positions,
                                           double rSmallMax) const {
    // Candidates k * relativeSkin, k = 1, 2, ..., the last the widest.
    constexpr std::size_t kMaxCandidates = 8;
    double const base = m_config.relativeSkin;
    double const widest = m_config.widestRelativeSkin;
    std::size_t const n =
        std::min(kMaxCandidates, static_cast<std::size_t>(std::ceil(widest / base - 1e-9)));
    auto const candidate = [&](std::size_t k) { return std::min(widest, (k + 1) * base); };
    std::array<double, kMaxCandidates> reach{};
    for (std::size_t k = 0; k < n; ++k)
        reach[k] = candidate(k) * rSmallMax + m_stats.slack;
    // Pairs listed by each candidate (the small ones: the large spheres are few).
    std::array<std::size_t, kMaxCandidates> listed{};
    m_cells.forEachOverlap([&](std::size_t a, std::size_t b) {
        double const gap = (positions[a] - positions[b]).norm() - ps.radius(a) - ps.radius(b);
        for (std::size_t k = 0; k < n; ++k)
            listed[k] += gap < reach[k] ? 1 : 0;
    });
    // The widest whose list is at most an eighth longer than relativeSkin's.
    std::size_t chosen = 0;
    for (std::size_t k = 1; k < n; ++k)
        if (listed[k] <= listed[0] + listed[0] / 8)
            chosen = k;
    return candidate(chosen);
}

} // namespace regolith::particles
