// ContactDetector's choice of the Verlet list's skin for the scene (ContactDetector.hpp, "A
// skin for the scene").
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::particles {

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
