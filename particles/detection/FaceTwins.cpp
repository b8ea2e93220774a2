/// Pairs across a periodic face of a region that spans the domain along that axis
/// (ContactDetector's class comment, "Pairs across a periodic face"): which instance of such a
/// pair the list settles, and when the settlement breaks.
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

namespace {

/// Whether `region` covers `frame`'s domain along axis d: the region then holds every image
/// instance of a pair that lies inside it along the other axes.
bool spans(core::AABB const& region, PeriodicFrame const& frame, int d) {
    return region.min[d] <= frame.domain.min[d] && region.max[d] >= frame.domain.max[d];
}

} // namespace

bool ContactDetector::holdsFaceTwins(core::AABB const& region, PeriodicFrame const& frame) const {
    bool periodicSpan = false;
    for (int d = 0; d < 3; ++d)
        periodicSpan |= frame.periodic[static_cast<std::size_t>(d)] && spans(region, frame, d);
    return m_config.settleFaceTwins && periodicSpan;
}

void ContactDetector::findFaceTwins(ParticleStorage const& ps, core::AABB const& region,
                                    PeriodicFrame const& frame, double rounding) {
    m_listings.assign(m_list.numPairs(), Listing::Drop);
    m_list.forEachPair([&](std::size_t ka, std::size_t kb, std::size_t p) {
        VerletList::Id a = VerletList::idOf(ps, ka), b = VerletList::idOf(ps, kb);
        m_listings[p] = settleListed(ps, a, b, ka, kb, region, frame, rounding);
        if (m_listings[p] != Listing::Open)
            return;
        // i's master: the one copy of i that nothing but a wrap replaces.
        if (!ps.flags(ka).isMaster() || !isZero(ps.image(ka)))
            return;
        if (!oneImageInstance(ps.radius(ka) + ps.radius(kb) + m_config.range, frame, rounding))
            return;
        if (!holdsFacePair(ps, ka, kb, a, b, region, frame, rounding))
            return;
        m_twins.push_back(
            {FaceTwinKey{ps.uid(ka), ps.uid(kb),
                         detection_detail::imageDifference(ps.image(kb), ps.image(ka))},
             a, b, 0});
    });
    std::sort(m_twins.begin(), m_twins.end(),
              [](FaceTwin const& x, FaceTwin const& y) { return x.key < y.key; });
}

bool ContactDetector::holdsFacePair(ParticleStorage const& ps, std::size_t ka, std::size_t kb,
                                    VerletList::Id a, VerletList::Id b, core::AABB const& region,
                                    PeriodicFrame const& frame, double rounding) const {
    core::Vec3 const period = frame.period();
    core::Vec3 const xi = localPosition(m_list.reference(a), ps.image(ka), period);
    core::Vec3 const x = localPosition(m_list.reference(b), ps.image(kb), period);
    // Along an axis the region does not span (a face shared with another region), the pair's
    // ownership point and i's master stay inside where the region emits while the list holds:
    // every instance's point wraps into this region, so no other evaluates the pair, and i's
    // master neither migrates nor wraps there.
    core::AABB const emits = emittingBox(region, frame);
    double const reach = listedReach(ps, ka, kb, rounding) + rounding;
    double const motion = listMotion(rounding) + rounding;
    for (int d = 0; d < 3; ++d) {
        double const mid = 0.5 * (xi[d] + x[d]);
        if (!spans(region, frame, d) &&
            !(mid - reach > emits.min[d] && mid + reach < emits.max[d] &&
              xi[d] - motion > emits.min[d] && xi[d] + motion < emits.max[d]))
            return false;
    }
    // j's copy at its image exists while the list holds: its ball reaches into the region by
    // more than the motion from its reference (the synchronisation keeps a copy wherever a
    // ball overlaps a region). j's master lives until it wraps or migrates, which kills the
    // pair (forgetDeadFaceTwins).
    if (ps.flags(kb).isMaster() && isZero(ps.image(kb)))
        return true;
    double outside2 = 0.0;
    for (int d = 0; d < 3; ++d) {
        double const out = std::max({region.min[d] - x[d], x[d] - region.max[d], 0.0});
        outside2 += out * out;
    }
    return std::sqrt(outside2) + listMotion(rounding) < ps.radius(kb);
}

ContactDetector::FaceTwin* ContactDetector::faceTwinOf(ParticleStorage const& ps, std::size_t ka,
                                                       std::size_t kb) {
    FaceTwinKey const key{ps.uid(ka), ps.uid(kb),
                          detection_detail::imageDifference(ps.image(kb), ps.image(ka))};
    auto const t =
        std::lower_bound(m_twins.begin(), m_twins.end(), key,
                         [](FaceTwin const& x, FaceTwinKey const& k) { return x.key < k; });
    return t == m_twins.end() || t->key != key ? nullptr : &*t;
}

void ContactDetector::keepFaceTwinsAtShift(ParticleStorage& ps, double rounding) {
    // A settled face pair holds on while it is open and j's copy still outlives the list, now
    // measured from the shifted references. The others end here: every instance keeps the
    // rule from now on (their twins come back from the parked pairs); the springs, and i's
    // images' histories, go back as when a grain wraps.
    std::erase_if(m_twins, [&](FaceTwin const& t) {
        VerletList::Id a = t.a, b = t.b;
        std::size_t ka = 0, kb = 0;
        if (settleListed(ps, a, b, ka, kb, m_listRegion, m_listFrame, rounding) == Listing::Open &&
            holdsFacePair(ps, ka, kb, a, b, m_listRegion, m_listFrame, rounding))
            return false;
        if (m_springsLive && keepsSpring(m_list.mode(t.pair))) {
            writeBackSpring(ps, m_list.indexOf(t.a), t.key.j, m_list.spring(t.pair),
                            m_list.hint(t.pair));
            writeBackFaceTwin(ps, t);
        }
        return true;
    });
}

PairMode ContactDetector::faceTwinMode(ParticleStorage const& ps, std::size_t ka, std::size_t kb,
                                       VerletList::Id a, VerletList::Id b,
                                       PeriodicFrame const& frame, double rounding) const {
    if (!m_config.keepSprings)
        return PairMode::Owned;
    core::Vec3 const period = frame.period();
    double const apart = (localPosition(m_list.reference(b), ps.image(kb), period) -
                          localPosition(m_list.reference(a), ps.image(ka), period))
                             .norm();
    return pressedWhileListed(apart, ps.radius(ka) + ps.radius(kb), rounding)
               ? PairMode::KeptPressedAcross
               : PairMode::Kept;
}

bool ContactDetector::faceTwinAlive(FaceTwin const& t) const {
    return m_list.indexOf(t.a) != VerletList::kDead && m_list.indexOf(t.b) != VerletList::kDead;
}

void ContactDetector::forgetDeadFaceTwins(ParticleStorage& ps) {
    // A settled face pair dies with a grain that wraps: the synchronisation then replaces every
    // copy of that grain in the block, so every instance of the pair dies with it (its twins
    // too), and the instances of the new copies arrive, keeping the rule (PairMode::Check)
    // until the next rebuild. It dies too when j's master at image zero migrates (its copy
    // here is replaced): the instance that arrives keeps the rule, and its parked twins are not
    // needed, as the point of two copies at image zero lies in the domain. The spring goes
    // back to the histories now, where they read it.
    std::erase_if(m_twins, [&](FaceTwin const& t) {
        if (faceTwinAlive(t))
            return false;
        if (m_springsLive)
            writeBackFaceTwin(ps, t);
        return true;
    });
}

void ContactDetector::writeBackFaceTwin(ParticleStorage& ps, FaceTwin const& t) const {
    if (!keepsSpring(m_list.mode(t.pair)))
        return;
    // i's master, found by uid once a wrap replaced it (in this region: holdsFacePair).
    std::size_t const i =
        faceTwinAlive(t) ? std::size_t{m_list.indexOf(t.a)} : ps.find(t.key.i, kNoImage);
    if (i == ParticleStorage::kNotFound)
        return;            // i left the domain through an open face
    if (!faceTwinAlive(t)) // (a live one's went back with the other kept pairs')
        writeBackSpring(ps, i, t.key.j, m_list.spring(t.pair), m_list.hint(t.pair));
    // The synchronisation copied i's stale history to i's other images, which an instance of
    // the pair keeping the rule may read in this very pass (after a wrap, or in the rebuilt
    // list): they get the master's again, as the next synchronisation would give them. (Those
    // images lie within one period of the master, on the periodic axes: the pair's reach is
    // under half of it.)
    auto const reach = [&](std::size_t axis) {
        return static_cast<std::int8_t>(m_listFrame.periodic[axis] ? 1 : 0);
    };
    for (std::int8_t x = -reach(0); x <= reach(0); ++x)
        for (std::int8_t y = -reach(1); y <= reach(1); ++y)
            for (std::int8_t z = -reach(2); z <= reach(2); ++z) {
                std::size_t const k = ps.find(t.key.i, CopyImage{x, y, z});
                if (k != ParticleStorage::kNotFound && k != i)
                    ps.history(k).assign(ps.history(i).entries());
            }
}

} // namespace regolith::particles
