#include "particles/detection/ContactDetector.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

namespace regolith::particles {

using Index = ParticleStorage::Index;
using detection_detail::imageDifference;
using detection_detail::PairRule;

core::AABB everywhere() {
    double const inf = std::numeric_limits<double>::infinity();
    return core::AABB{core::Vec3::Constant(-inf), core::Vec3::Constant(inf)};
}

ContactDetector::ContactDetector(DetectorConfig config)
    : m_config(config) {
    if (!(m_config.skin >= 0.0) || !(m_config.largeRadius >= 0.0) ||
        !(m_config.largeFactor >= 1.0) || !(m_config.range >= 0.0) ||
        !std::isfinite(m_config.range))
        throw core::InputError("contact detection: skin and large_radius must be >= 0, "
                               "large_factor >= 1 and the interaction range finite and >= 0");
}

double ContactDetector::largeThreshold(ParticleStorage const& ps) {
    if (m_config.largeRadius > 0.0)
        return m_config.largeRadius;
    // Median by selection, O(N).
    m_scratch.assign(ps.radii().begin(), ps.radii().end());
    auto mid = m_scratch.begin() + static_cast<std::ptrdiff_t>(m_scratch.size() / 2);
    std::nth_element(m_scratch.begin(), mid, m_scratch.end());
    double const median = *mid;
    std::vector<double>().swap(m_scratch); // 8 bytes per copy, needed only here
    return m_config.largeFactor * median;
}

LocalPositions ContactDetector::classify(ParticleStorage const& ps, PeriodicFrame const& frame,
                                         double& rSmallMax, double& scale) {
    core::Vec3 const period = frame.period();
    bool shifted = false;
    for (Index k = 0, n = ps.size(); k < n; ++k) {
        CopyImage const& image = ps.image(k);
        if (isZero(image))
            continue;
        shifted = true;
        for (std::size_t a = 0; a < 3; ++a)
            if (image[a] != 0 && (!frame.periodic[a] || frame.wrapped[a]))
                throw core::Error("contact detection: uid " + std::to_string(ps.uid(k)) +
                                  " has a periodic image on axis " + std::to_string(a) +
                                  ", which is not periodic or wraps in the detection frame");
    }
    LocalPositions const positions = shifted ? LocalPositions(ps.positions(), ps.images(), period)
                                             : LocalPositions(ps.positions());

    double const cut = largeThreshold(ps);
    rSmallMax = 0.0;
    double rMax = 0.0, xMax = 0.0;
    for (Index k = 0, n = ps.size(); k < n; ++k) {
        double const r = ps.radius(k);
        rMax = std::max(rMax, r);
        xMax = std::max(xMax, positions[k].cwiseAbs().maxCoeff());
        if (r > cut) {
            m_large.push_back(k);
        } else {
            m_small.push_back(static_cast<std::uint32_t>(k));
            rSmallMax = std::max(rSmallMax, r);
        }
    }
    scale = xMax + 2.0 * rMax;
    m_stats.largeThreshold = cut;
    m_stats.smallSpheres = m_small.size();
    m_stats.largeSpheres = m_large.size();
    return positions;
}

LocalPositions ContactDetector::bin(ParticleStorage const& ps, PeriodicFrame const& frame,
                                    double skin) {
    m_stats = DetectorStats{};
    m_small.clear();
    m_large.clear();
    double rSmallMax = 0.0, scale = 0.0;
    LocalPositions const positions = classify(ps, frame, rSmallMax, scale);
    // Local positions (x + k * period) differ from the canonical geometry of PairRule by a few
    // roundings of numbers up to `scale`, and so does the cell assignment: 64 ulps of the
    // largest coordinate cover both, so the candidates include every canonical overlap.
    if (skin != 0.0)
        scale *= 2.0; // a Verlet list: room for copies that arrive later (addArrivals)
    double const slack = 64.0 * std::numeric_limits<double>::epsilon() * scale;
    m_stats.slack = slack;
    if (skin < 0.0) // relative: a fraction of the small radius
        skin = -skin * rSmallMax;
    m_stats.skin = skin;
    m_listScale = scale;

    // The candidates reach the model's interaction range beyond the radii too.
    double const range = m_config.range;
    double edge = 2.0 * rSmallMax + skin + range;
    if (!(edge > 0.0)) // only zero radii: any positive edge is right
        edge = 1.0;
    LinkedCells::Wrap wrap;
    for (std::size_t a = 0; a < 3; ++a)
        wrap.axes[a] = frame.periodic[a] && frame.wrapped[a];
    wrap.min = frame.domain.min;
    wrap.max = frame.domain.max;
    m_cells.build(positions, ps.radii(), m_small, edge + 2.0 * slack,
                  m_config.maxCellsPerSphere * std::max<std::size_t>(m_small.size(), 1),
                  slack + skin + range, wrap);
    // The cells hold the small spheres now (their members): the list's 4 bytes per copy
    // would only add to the peak while the Verlet list is built next.
    std::vector<std::uint32_t>().swap(m_small);
    m_stats.cellEdge = m_cells.edge();
    m_stats.cells = m_cells.numCells();
    return positions;
}

void ContactDetector::detect(ParticleStorage const& ps, WallList const& walls,
                             core::AABB const& region, PeriodicFrame const& frame,
                             ContactList& out) {
    out.clear();
    if (m_springsLive)
        throw core::Error("contact detection: a detect without the list while it kept springs "
                          "that were not written back");
    m_list.invalidate(); // the cells are rebuilt without the skin
    if (ps.empty()) {
        m_stats = DetectorStats{};
        m_small.clear();
        m_large.clear();
        m_cells.build({}, {}, {}, 1.0, 1); // forget the last grid (spatialOrder)
        return;
    }
    LocalPositions const positions = bin(ps, frame, 0.0);
    PairRule const rule(ps, region, frame, m_stats, m_config.range);
    auto emit = [&](std::size_t a, std::size_t b, double = 0.0, CopyImage shift = kNoImage) {
        rule(a, b, out.pairs, shift);
    };
    m_cells.forEachOverlap(emit);
    largePass(positions, ps, frame, m_stats.slack + m_config.range, emit);
    wallPass(ps, walls, out);

    if (m_config.sortByUid)
        sortByUid(ps, out);
}

void ContactDetector::detect(ParticleStorage& ps, WallList const& walls, core::AABB const& region,
                             PeriodicFrame const& frame, ContactList& out) {
    if (!listed()) {
        detect(std::as_const(ps), walls, region, frame, out);
        return;
    }
    out.clear();
    updateList(ps, region, frame);
    writeBackCarried(ps);
    listedPass(
        ps, region, frame, out, [](Contact const&, std::uint8_t&) {}, true);
    wallPass(ps, walls, out);
    if (m_config.sortByUid)
        sortByUid(ps, out);
}

void ContactDetector::rebuildList(ParticleStorage& ps, core::AABB const& region,
                                  PeriodicFrame const& frame) {
    m_listRegion = region;
    m_listFrame = frame;
    m_largeIds.clear();
    m_spreadOut = false;
    if (ps.empty()) {
        m_stats = DetectorStats{};
        m_small.clear();
        m_large.clear();
        m_cells.build({}, {}, {}, 1.0, 1);
        m_listScale = 0.0; // the first arrival rebuilds
        m_list.restart(ps, 0.0);
        m_depths.clear();
        return;
    }
    // A skin for the scene: every kSkinChoiceEvery-th rebuild bins with the widest one and
    // chooses; the others bin with the choice (negative: relative to the small radius).
    constexpr std::uint32_t kSkinChoiceEvery = 16;
    bool const choose = widens() && m_rebuilds % kSkinChoiceEvery == 0;
    ++m_rebuilds;
    double skin = m_config.skin > 0.0 ? m_config.skin : -m_config.relativeSkin;
    if (choose)
        skin = -m_config.widestRelativeSkin;
    else if (widens() && m_relativeSkin > 0.0)
        skin = -m_relativeSkin;
    LocalPositions const positions = bin(ps, frame, skin);
    double const binned = m_stats.skin; // the reach of the cells' candidates
    if (choose) {
        double const rSmallMax = binned / m_config.widestRelativeSkin;
        m_relativeSkin = chooseRelativeSkin(ps, positions, rSmallMax);
        m_stats.skin = m_relativeSkin * rSmallMax;
    }
    m_listSkin = m_stats.skin;
    m_list.restart(ps, m_listSkin); // ids = indices, as the cells' members
    m_builtRadiusMin = std::numeric_limits<double>::infinity();
    m_builtRadiusMax = 0.0;
    for (double const r : ps.radii()) {
        m_builtRadiusMin = std::min(m_builtRadiusMin, r);
        m_builtRadiusMax = std::max(m_builtRadiusMax, r);
    }
    // Binned wider than the list's skin: the candidates beyond it are left out (in the local
    // frame, which the slack covers, as the cells' own test). The cells' bound on how far
    // apart a pair is tells the per-step pass when it may first overlap
    // (VerletList::forEachNearPair); the large pass does not measure it.
    double const slack = m_stats.slack;
    core::Vec3 const period = frame.period();
    auto const add = [&](std::size_t a, std::size_t b,
                         double apart = -std::numeric_limits<double>::infinity(),
                         CopyImage shift = kNoImage) {
        if (m_listSkin < binned) {
            double const reach = ps.radius(a) + ps.radius(b) + m_listSkin + m_config.range + slack;
            if (!((localPosition(positions[b], shift, period) - positions[a]).squaredNorm() <
                  reach * reach))
                return;
        }
        m_list.addPair(static_cast<VerletList::Id>(a), static_cast<VerletList::Id>(b),
                       VerletList::gapBelow(apart - m_config.range - slack), shift);
    };
    m_cells.forEachOverlap(add);
    largePass(positions, ps, frame, slack + binned + m_config.range, add);
    for (Index k : m_large)
        m_largeIds.push_back(static_cast<VerletList::Id>(k));
    m_depths.start(m_list, region, frame);
    classifyListed(ps, region, frame, 0);
}

template <class F>
void ContactDetector::largePass(LocalPositions const& pos, ParticleStorage const& ps,
                                PeriodicFrame const& frame, double reachSlack, F&& f) {
    if (m_large.empty())
        return;
    double const noGap = -std::numeric_limits<double>::infinity();
    // Large against small: the cells of the ball (their reach includes the skin).
    for (Index a : m_large) {
        m_stats.largeCellVisits +=
            m_cells.forEachOverlapWith(pos[a], ps.radius(a), [&](std::uint32_t b, CopyImage shift) {
                ++m_stats.largeCandidates;
                f(a, Index{b}, noGap, shift);
            });
    }
    if (frame.anyWrapped()) { // large against large, every image across the wrapped faces
        core::Vec3 const period = frame.period();
        for (std::size_t s = 0; s < m_large.size(); ++s)
            for (std::size_t t = s + 1; t < m_large.size(); ++t) {
                Index const a = m_large[s], b = m_large[t];
                double const reach = ps.radius(a) + ps.radius(b) + reachSlack;
                ++m_stats.largeCandidates;
                frame.forEachWrappedImage(pos[a] - pos[b], reach, [&](CopyImage const& shift) {
                    if ((localPosition(pos[b], shift, period) - pos[a]).squaredNorm() <
                        reach * reach)
                        f(a, b, noGap, shift);
                });
            }
        return;
    }
    // Large against large: sort by the lower bound along the axis where the large centres
    // spread most (fewest overlapping intervals), sweep while the next lower bound is below
    // the current upper bound.
    core::Vec3 lo = pos[m_large[0]], hi = lo;
    for (Index k : m_large) {
        lo = lo.cwiseMin(pos[k]);
        hi = hi.cwiseMax(pos[k]);
    }
    Eigen::Index axis = 0;
    (hi - lo).maxCoeff(&axis);
    auto lower = [&](Index k) { return pos[k][axis] - ps.radius(k); };
    std::sort(m_large.begin(), m_large.end(), [&](Index x, Index y) {
        return std::tuple(lower(x), ps.uid(x), ps.image(x)) <
               std::tuple(lower(y), ps.uid(y), ps.image(y));
    });
    for (std::size_t s = 0; s < m_large.size(); ++s) {
        Index const a = m_large[s];
        double const upper = pos[a][axis] + ps.radius(a) + reachSlack;
        for (std::size_t t = s + 1; t < m_large.size() && lower(m_large[t]) < upper; ++t) {
            Index const b = m_large[t];
            ++m_stats.largeCandidates;
            double const reach = ps.radius(a) + ps.radius(b) + reachSlack;
            if ((pos[b] - pos[a]).squaredNorm() < reach * reach)
                f(a, b, noGap, kNoImage);
        }
    }
}

void ContactDetector::sortByUid(ParticleStorage const& ps, ContactList& out) const {
    auto pairKey = [&ps](Contact const& c) {
        return std::tuple(ps.uid(c.i), ps.uid(c.j), c.shiftJ.x(), c.shiftJ.y(), c.shiftJ.z());
    };
    std::sort(out.pairs.begin(), out.pairs.end(),
              [&](Contact const& x, Contact const& y) { return pairKey(x) < pairKey(y); });
    std::sort(
        out.walls.begin(), out.walls.end(), [&ps](WallContact const& x, WallContact const& y) {
            return std::pair(ps.uid(x.particle), x.wall) < std::pair(ps.uid(y.particle), y.wall);
        });
}

std::vector<std::size_t> ContactDetector::spatialOrder() const {
    auto const cells = m_cells.membersInCellOrder();
    std::vector<std::size_t> order(cells.begin(), cells.end());
    order.insert(order.end(), m_large.begin(), m_large.end());
    return order;
}

void ContactDetector::release() {
    if (m_springsLive)
        throw core::Error("contact detection: released while it kept springs that were not "
                          "written back");
    *this = ContactDetector(m_config);
}

std::size_t ContactDetector::bytes() const {
    return m_cells.bytes() + m_small.capacity() * sizeof(std::uint32_t) +
           m_large.capacity() * sizeof(std::size_t) + m_scratch.capacity() * sizeof(double) +
           m_arrivalLanes.capacity() * sizeof(double) + m_arrivalHits.capacity() +
           m_depths.bytes() + m_carried.bytes() + m_deepIds.capacity();
}

} // namespace regolith::particles
