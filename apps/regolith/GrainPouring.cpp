#include "apps/regolith/GrainPouring.hpp"

#include "apps/regolith/InsertSection.hpp"
#include "core/log/Log.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/checkpoint/RestoreGrains.hpp"
#include "particles/generators/GrainInsertion.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace regolith::apps {

GrainPouring::GrainPouring(core::Comm const& comm, SceneDescription const& scene,
                           particles::LocalParticles const& local)
    : m_comm(&comm)
    , m_scene(&scene) {
    std::size_t const entries = scene.inserts.size();
    for (std::size_t e = 0; e < entries; ++e) {
        checkBatchDensity(scene.inserts[e], e, scene.time.dt);
        m_batch.push_back(batchSize(scene.inserts[e], scene.time.dt));
    }
    if (entries == 0)
        return;
    // A restart's grains: per entry, one past the largest number among the masters.
    std::vector<std::int64_t> next(entries, 0);
    for (particles::BlockParticles const& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) {
            long const e = particles::insertEntryOf(bp.particles.uid(i));
            if (e >= 0 && static_cast<std::size_t>(e) < entries)
                next[static_cast<std::size_t>(e)] = std::max(
                    next[static_cast<std::size_t>(e)],
                    static_cast<std::int64_t>(particles::uidCounter(bp.particles.uid(i))) + 1);
        });
    comm.allReduceInPlace(std::span<std::int64_t>(next), core::ReduceOp::Max);
    m_next = std::move(next);
    m_warnedShort.assign(m_next.size(), false);
}

bool GrainPouring::due(std::int64_t stepsDone) const {
    for (std::size_t e = 0; e < m_next.size(); ++e)
        if (stepsDone > 0 && stepsDone % m_scene->inserts[e].every == 0 &&
            m_next[e] < m_scene->inserts[e].count)
            return true;
    return false;
}

namespace {

/// Whether the sphere (x, r) may reach into `box` grown by `reach`, with the minimum image
/// along periodic axes (`periodic[a]` > 0: the period).
bool nearBox(core::Vec3 const& x, double r, core::AABB const& box, double reach,
             particles::PeriodicLengths const& periodic) {
    double gap2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        double const centre = 0.5 * (box.min[a] + box.max[a]);
        double d = x[a] - centre;
        if (double const len = periodic[static_cast<std::size_t>(a)]; len > 0.0)
            d -= len * std::round(d / len);
        double const gap = std::max(std::abs(d) - 0.5 * (box.max[a] - box.min[a]), 0.0);
        gap2 += gap * gap;
    }
    double const reachAll = reach + r;
    return gap2 < reachAll * reachAll;
}

} // namespace

bool GrainPouring::afterStep(std::int64_t stepsDone, coupling::Placement& placement,
                             particles::WallList const& walls) {
    if (!due(stepsDone))
        return false;
    particles::LocalParticles& local = *placement.local;
    domain::ForestSpec const& forest = m_scene->forest;
    particles::PeriodicLengths periodic{};
    for (std::size_t a = 0; a < 3; ++a)
        periodic[a] = forest.periodic[a] ? forest.domain.extent()[static_cast<int>(a)] : 0.0;
    double largest = 0.0;
    for (particles::BlockParticles const& bp : local.blocks())
        bp.particles.forEachMaster(
            [&](std::size_t i) { largest = std::max(largest, bp.particles.radius(i)); });
    largest = m_comm->allReduce(largest, core::ReduceOp::Max);

    std::vector<io::GrainState> added;
    std::vector<particles::GrainInit> placedBefore; // earlier entries' grains of this batch
    for (std::size_t e = 0; e < m_next.size(); ++e) {
        particles::InsertSpec const& spec = m_scene->inserts[e];
        if (stepsDone % spec.every != 0 || m_next[e] >= spec.count)
            continue;
        auto const batch = static_cast<std::uint64_t>(stepsDone / spec.every);
        std::int64_t const target =
            std::min(spec.count, static_cast<std::int64_t>(batch) * m_batch[e]);
        // Every rank gathers the masters that may touch the region: the same set everywhere
        // (in another order, which the placement does not depend on).
        core::AABB const bounds = spec.region.bounds();
        std::vector<double> mine;
        for (particles::BlockParticles const& bp : local.blocks())
            bp.particles.forEachMaster([&](std::size_t i) {
                core::Vec3 const& x = bp.particles.position(i);
                double const r = bp.particles.radius(i);
                if (nearBox(x, r, bounds, spec.radiusMax, periodic))
                    mine.insert(mine.end(), {x.x(), x.y(), x.z(), r});
            });
        std::vector<double> const all = m_comm->allGatherVarying<double>(mine);
        std::vector<particles::PlacedSphere> near;
        for (std::size_t k = 0; k + 3 < all.size(); k += 4)
            near.push_back({core::Vec3(all[k], all[k + 1], all[k + 2]), all[k + 3]});
        for (particles::GrainInit const& g : placedBefore)
            near.push_back({g.position, g.radius});
        std::vector<particles::GrainInit> const placed =
            particles::placeBatch(spec, e, batch, static_cast<std::uint64_t>(m_next[e]),
                                  target - m_next[e], near, walls, periodic);
        if (static_cast<std::int64_t>(placed.size()) < target - m_next[e] && !m_warnedShort[e]) {
            m_warnedShort[e] = true; // once per entry: the summary's `inserted` counts the rest
            core::log::warn("insert[{}]: after step {}, {} of {} grains found no place without "
                            "overlap in {} attempts each; they wait for the next batch (later "
                            "batches short of room are not reported again)",
                            e, stepsDone,
                            target - m_next[e] - static_cast<std::int64_t>(placed.size()),
                            target - m_next[e], spec.attempts);
        }
        m_next[e] += static_cast<std::int64_t>(placed.size());
        m_inserted += static_cast<std::int64_t>(placed.size());
        for (particles::GrainInit const& g : placed) {
            placedBefore.push_back(g);
            io::GrainState s;
            s.uid = g.uid;
            s.position = g.position;
            s.velocity = g.velocity;
            s.radius = g.radius;
            s.mass = g.mass;
            s.type = g.type;
            added.push_back(std::move(s));
        }
    }
    if (added.empty())
        return false;
    // The masters move to a fresh LocalParticles with the new grains (rank 0 hands those in:
    // every rank placed the same), each to the block containing it, as in a rebalance.
    std::vector<io::GrainState> grains = io::collectMasters(local);
    if (m_comm->rank() == 0)
        grains.insert(grains.end(), added.begin(), added.end());
    local = particles::LocalParticles(*placement.particleForest);
    io::restoreGrains(*m_comm, local, grains, "inserting grains");
    return true;
}

} // namespace regolith::apps
