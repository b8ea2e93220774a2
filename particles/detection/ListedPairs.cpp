/// Settling the Verlet list's pairs when they are listed (ContactDetector's class comment,
/// "Settled pairs and the fused loop"): what the contact-point rule will answer for a pair while
/// the list holds, and the mode each pair gets from it (PairMode; the kept springs' modes in
/// KeptSprings.cpp).
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace regolith::particles {

void ContactDetector::orderListed(ParticleStorage const& ps, VerletList::Id& a, VerletList::Id& b,
                                  std::size_t& ka, std::size_t& kb, CopyImage& shift) const {
    ka = m_list.indexOf(a);
    kb = m_list.indexOf(b);
    if (ps.uid(kb) < ps.uid(ka)) {
        std::swap(a, b);
        std::swap(ka, kb);
        shift = negated(shift);
    }
}

double ContactDetector::listedReach(ParticleStorage const& ps, std::size_t ka, std::size_t kb,
                                    double rounding) const {
    double const ri = ps.radius(ka), rj = ps.radius(kb);
    return ownershipReach(ri, rj, m_listSkin, rounding + 1e-12 * (ri + rj + m_listSkin));
}

VerletList::Decision ContactDetector::settlePair(ParticleStorage const& ps, VerletList::Id& a,
                                                 VerletList::Id& b, CopyImage& shift,
                                                 std::size_t& ka, std::size_t& kb,
                                                 core::AABB const& region,
                                                 PeriodicFrame const& frame,
                                                 double rounding) const {
    constexpr VerletList::Decision drop{VerletList::kDrop, false};
    constexpr VerletList::Decision check{static_cast<int>(PairMode::Check), false};
    // Emitted whenever the two overlap: whether it stays in the block, and its mode.
    auto const always = [&]() -> VerletList::Decision {
        // (A pair across a wrapped face joins copies near it: not deep inside, never kept.)
        bool const stays = isZero(shift) && staysInBlock(ps, ka, kb, a, b, region, frame, rounding);
        return {static_cast<int>(settledMode(ps, ka, kb, a, b, stays, rounding)), stays};
    };
    orderListed(ps, a, b, ka, kb, shift);
    if (ps.uid(ka) == ps.uid(kb))
        return drop; // a grain and its own periodic image: never a contact
    if (ps.flags(ka).isFixed() && ps.flags(kb).isFixed())
        return check; // rare: the rule skips them
    double const reach = listedReach(ps, ka, kb, rounding);
    // Both reference centres deeper than the reach (with the rounding once more): so is their
    // midpoint, and settleOwnership answers Always.
    if (m_depths.deeperThan(m_list, ps, a, b, reach + rounding))
        return always();
    core::Vec3 const period = frame.period();
    core::Vec3 const mid =
        0.5 * (localPosition(m_list.reference(a), ps.image(ka), period) +
               localPosition(m_list.reference(b), addImages(ps.image(kb), shift), period));
    switch (settleOwnership(mid, reach, region, frame)) {
    case Settled::Never:
        return drop;
    case Settled::Always:
        return always();
    case Settled::Open:
        break;
    }
    return check;
}

double ContactDetector::settledDepth(double rounding) const {
    // listedReach's terms at their largest (the rebuild's radii bound every listed pair's),
    // then the depths settlePair and staysInBlock ask for; a relative 1e-9 more covers the
    // sums' rounding (a pair near the bound goes the long way, with the same answer).
    double const rMin = m_builtRadiusMin, rMax = m_builtRadiusMax;
    double const reach =
        0.5 * m_listSkin + 0.5 * (rMax - rMin) + rounding + 1e-12 * (2.0 * rMax + m_listSkin);
    return (std::max(reach, listMotion(rounding)) + rounding) * (1.0 + 1e-9);
}

std::vector<std::uint8_t> ContactDetector::deepMasters(ParticleStorage const& ps,
                                                       PeriodicFrame const& frame,
                                                       double rounding) const {
    // The rebuild's ids are its storage indices.
    std::size_t const n = m_list.builtSize();
    std::vector<std::uint8_t> deep(n, 0);
    if (n == 0 || !std::isfinite(m_builtRadiusMax) ||
        !oneImageInstance(2.0 * m_builtRadiusMax, frame, rounding))
        return deep;
    double const bound = settledDepth(rounding);
    for (std::size_t k = 0; k < n; ++k) {
        auto const id = static_cast<VerletList::Id>(k);
        deep[k] = ps.flags(k).isMaster() && !ps.flags(k).isFixed() && isZero(ps.image(k)) &&
                  m_depths.of(m_list, ps, id) > bound;
    }
    return deep;
}

void ContactDetector::classifyListed(ParticleStorage const& ps, core::AABB const& region,
                                     PeriodicFrame const& frame, std::size_t first) {
    // 4 x the candidate slack (64 ulps of the coordinate scale) covers the rounding of the
    // midpoint, the ownership point and the wrap, which are a few ulps of the same numbers.
    // The list's reference positions are floats: the midpoint is off by at most their slack.
    double const rounding = 4.0 * m_stats.slack + m_list.referenceSlack();
    // At a rebuild most pairs join two masters at image zero deeper inside the block than
    // any pair's ownership reach and the list's motion: settlePair would answer "stays, and
    // keeps its spring" for them after reading both copies' flags, images and depths per
    // pair. Those copies are found once; their pairs only need the canonical order and
    // settledMode's pressed test.
    std::vector<std::uint8_t> const deep = first == 0 && m_depths.unshifted()
                                               ? deepMasters(ps, frame, rounding)
                                               : std::vector<std::uint8_t>{};
    m_list.classifyFrom(first, [&](VerletList::Id& a, VerletList::Id& b, CopyImage& shift) {
        std::size_t ka = 0, kb = 0;
        if (a < deep.size() && b < deep.size() && (deep[a] & deep[b]) != 0 && isZero(shift)) {
            orderListed(ps, a, b, ka, kb, shift);
            return VerletList::Decision{
                static_cast<int>(settledMode(ps, ka, kb, a, b, true, rounding)), true};
        }
        return settlePair(ps, a, b, shift, ka, kb, region, frame, rounding);
    });
}

} // namespace regolith::particles
