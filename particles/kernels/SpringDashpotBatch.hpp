#pragma once
/// The spring-dashpot model over a batch of pair contacts at once, for the fused contact loop
/// (DemStep): the overlapping pairs the Verlet list finds (PairOverlap: the two copies and the
/// periodic shift, no geometry) are collected a batch at a time, their geometry and forces
/// computed in one branch-free loop the compiler vectorises across contacts, and the shares
/// handed to the sink in the order the pairs were found.
///
/// Why: evaluated one by one (evaluatePair), a contact cost ~540 instructions of scalar Eigen
/// code on 3-vectors (callgrind, static lattice), much of it moving the same numbers between
/// structs; here each lane is a plain double array and the model runs 4 contacts per AVX2
/// instruction, 8 per AVX-512 one where the machine has it (REGOLITH_LANE_CODEGEN: the loop is
/// latency-bound, so wider lanes pay even where the units are 256 bits wide;
/// cmake/RegolithTargets.cmake). The grains' state is
/// loaded by index, not copied pair by pair: centres, velocities and spins eight contacts at a
/// time, transposed in registers, and the scalars (inverse masses and inertias, radii) by
/// gathers inside the loop ("Loads by index and transposed").
///
/// Same bits as overlapGeometry followed by evaluatePair with SpringDashpot: every lane computes
/// the same IEEE operations in the same order as overlapGeometry (normal, penetration, point),
/// pairState, SpringDashpot::operator(), tangentialForce, projectSpring and rollingResistance
/// (model A's couple or model C's spring; branches become selects of values computed either way),
/// so results do not depend on the path or the vector width
/// (tests/particles/SpringDashpotBatchTest.cpp).
#include "core/math/Vec3.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/kernels/SpringDashpotParameters.hpp"
#include "particles/kernels/SpringDashpotWallBatch.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

namespace regolith::particles {

class SpringDashpotBatch {
public:
    static constexpr std::size_t kCapacity = 64;
    static_assert(kCapacity % 8 == 0, "evaluate loads the grains eight contacts at a time");

    [[nodiscard]] std::size_t size() const { return m_size; }
    [[nodiscard]] bool full() const { return m_size == kCapacity; }
    void clear() { m_size = 0; }

    /// Adds the overlapping pair `p` (canonical order, copies of the storage evaluate will
    /// read) with `entry`, its history entry (the tangential spring, written back after
    /// evaluate), `hint` (the entry's slot in i's ContactHistory, to find it again if the
    /// history moved) and, for a model with model C's rolling spring, `rolling`, the entry
    /// keyed rollingKey(uid(j)) (else nullptr). Pre: !full().
    void add(PairOverlap const& p, HistoryEntry& entry, std::uint8_t hint,
             HistoryEntry* rolling = nullptr);
    /// Adds the overlapping pair (i, j) (canonical order, j's periodic shift `shiftJ`: +0 for
    /// one image) whose spring `kept` lives beside a neighbour list (ContactDetector, "Springs
    /// kept beside the list"), with the spring the touch of pass `stamp` would leave it, but
    /// not stamped: the caller writes the entry (spring and stamp) after evaluate. Without
    /// model C's rolling spring. Pre: !full().
    [[gnu::always_inline]] void addKept(std::size_t i, std::size_t j, core::Vec3 const& shiftJ,
                                        KeptSpring& kept, std::uint32_t stamp) {
        std::size_t const k = m_size++;
        m_i[k] = static_cast<std::uint32_t>(i);
        m_j[k] = static_cast<std::uint32_t>(j);
        m_kept[k] = &kept; // (entry, hint and rolling entry are not read for a kept pair)
        m_shift[0][k] = shiftJ.x();
        m_shift[1][k] = shiftJ.y();
        m_shift[2][k] = shiftJ.z();
        // The spring ContactHistory::touch leaves: zero unless the contact continues.
        bool const continued = ContactHistory::continues(kept.stamp, stamp);
        m_s[0][k] = continued ? kept.spring.x() : 0.0;
        m_s[1][k] = continued ? kept.spring.y() : 0.0;
        m_s[2][k] = continued ? kept.spring.z() : 0.0;
    }

    /// addKept for the overlapping pairs of a block of a list whose pairs are all kept and join
    /// two copies in one image (shift +0): pair t (bit t of `hits`) joins copies i[t], j[t]
    /// and keeps its spring at springs[at[t]]. Adds them in the order of their bits until the
    /// batch is full and returns the bits not added. One loop over the hits with the batch's
    /// size and the arrays' addresses in registers: the pass over a packing's list hands
    /// over most of its contacts here.
    [[gnu::always_inline]] std::uint64_t addKeptHits(std::uint32_t const* i, std::uint32_t const* j,
                                                     std::uint32_t const* at, std::uint64_t hits,
                                                     KeptSpring* springs, std::uint32_t stamp) {
        std::size_t k = m_size;
        for (; hits != 0 && k < kCapacity; hits &= hits - 1, ++k) {
            auto const t = static_cast<std::size_t>(std::countr_zero(hits));
            KeptSpring& kept = springs[at[t]];
            m_i[k] = i[t];
            m_j[k] = j[t];
            m_kept[k] = &kept;
            m_shift[0][k] = 0.0;
            m_shift[1][k] = 0.0;
            m_shift[2][k] = 0.0;
            bool const continued = ContactHistory::continues(kept.stamp, stamp);
            m_s[0][k] = continued ? kept.spring.x() : 0.0;
            m_s[1][k] = continued ? kept.spring.y() : 0.0;
            m_s[2][k] = continued ? kept.spring.z() : 0.0;
        }
        m_size = k;
        return hits;
    }

    /// Evaluates every added contact of `ps` (the storage whose copies were added, its
    /// positions, motion, radii, masses and types unchanged since) with
    /// `model` and time step `dt`: afterwards force(k), torqueI(k), torqueJ(k) and spring(k)
    /// hold what overlapGeometry and evaluatePair would give (force on j, torques on i and j,
    /// the updated spring).
    void evaluate(ParticleStorage const& ps, SpringDashpot const& model, double dt);

    [[nodiscard]] std::size_t i(std::size_t k) const { return m_i[k]; }
    [[nodiscard]] std::size_t j(std::size_t k) const { return m_j[k]; }
    [[nodiscard]] std::uint8_t hint(std::size_t k) const { return m_hint[k]; }
    /// The history entry gathered with pair k (dangling if its history got an entry since).
    [[nodiscard]] HistoryEntry* entry(std::size_t k) const { return m_entry[k]; }
    /// The kept spring pair k came with (addKept), or nullptr.
    [[nodiscard]] KeptSpring* kept(std::size_t k) const { return m_kept[k]; }
    [[nodiscard]] core::Vec3 force(std::size_t k) const {
        return {m_f[0][k], m_f[1][k], m_f[2][k]};
    }
    [[nodiscard]] core::Vec3 torqueI(std::size_t k) const {
        return {m_ti[0][k], m_ti[1][k], m_ti[2][k]};
    }
    [[nodiscard]] core::Vec3 torqueJ(std::size_t k) const {
        return {m_tj[0][k], m_tj[1][k], m_tj[2][k]};
    }
    [[nodiscard]] core::Vec3 spring(std::size_t k) const {
        return {m_s[0][k], m_s[1][k], m_s[2][k]};
    }
    /// The rolling history entry gathered with pair k (nullptr without model C; dangling as
    /// entry(k)) and its updated spring.
    [[nodiscard]] HistoryEntry* rollingEntry(std::size_t k) const { return m_rollingEntry[k]; }
    [[nodiscard]] core::Vec3 rollingSpring(std::size_t k) const {
        return {m_rOut[0][k], m_rOut[1][k], m_rOut[2][k]};
    }

private:
    /// The storage's scalars the lane loop reads by index; restrict, so that GCC may gather
    /// from them (it cannot check a gather's overlap with the batch's stores at run time).
    struct GrainScalars {
        double const* __restrict invM;
        double const* __restrict invI;
        double const* __restrict rad;
        static GrainScalars of(ParticleStorage const& ps) {
            return {ps.invMasses().data(), ps.invInertias().data(), ps.radii().data()};
        }
    };
    using Parameters = spring_lanes::Parameters;
    using Rolling = spring_lanes::Rolling;
    /// evaluate's loop over the lanes, with `uniform`'s parameters in every lane or each
    /// lane's own (m_parameters).
    template <Rolling kRolling, bool kUniform>
    void evaluateLanes(GrainScalars g, Parameters uniform, double dt);
    /// Loads the centres of the contacts, eight at a time (the lanes beyond size() repeat
    /// contact 0's copies: computed, never read).
    void loadCentres(ParticleStorage const& ps);

    using Lane = std::array<double, kCapacity>;
    using Lane3 = std::array<Lane, 3>;

    std::size_t m_size = 0;
    std::array<std::uint32_t, kCapacity> m_i{}; ///< storage indices (a Verlet list's range)
    std::array<std::uint32_t, kCapacity> m_j{};
    std::array<std::uint8_t, kCapacity> m_hint{};
    std::array<HistoryEntry*, kCapacity> m_entry{};
    std::array<HistoryEntry*, kCapacity> m_rollingEntry{};
    std::array<KeptSpring*, kCapacity> m_kept{}; ///< with addKept, else nullptr
    // Inputs: centres x_i and x_j (j's periodic shift apart), velocities and spins (filled by
    // evaluate), the springs, tangential (updated in place) and rolling (model C).
    alignas(64) Lane3 m_xi, m_xj, m_shift, m_vi, m_vj, m_wi, m_wj;
    alignas(64) Lane3 m_s, m_r;
    // The pair's material parameters, from the tables (several materials only: with one, the
    // lanes read Parameters and these are neither filled nor read).
    spring_lanes::ParameterLanes<kCapacity> m_parameters;
    // Outputs (the rolling spring's with model C only).
    alignas(64) Lane3 m_f, m_ti, m_tj, m_rOut;
};

/// overlapGeometry and evaluatePair with SpringDashpot for a stream of overlapping pairs, in
/// batches: call it on each pair as found (with the pair's history slot hint), then finish().
/// Each pair's spring is touched (stamped) when it arrives, as evaluatePair does; the batch is
/// evaluated when full, before a pair whose spring an earlier pair of this pass touched (a pair
/// meeting through two periodic images must see the spring the first evaluation left), and at
/// finish(). `sink` receives the shares in arrival order, j's first: the same calls with the
/// same bits as evaluatePair on each contact in turn; it is copied for each batch, so it
/// refers to where the shares go rather than holding them. Not collective.
template <ContactSink Sink>
class BatchedSpringDashpot {
public:
    BatchedSpringDashpot(ParticleStorage& ps, SpringDashpot const& model, double dt,
                         std::uint32_t stamp, SpringDashpotBatch& batch, Sink& sink)
        : m_ps(ps)
        , m_model(model)
        , m_dt(dt)
        , m_stamp(stamp)
        , m_batch(batch)
        , m_sink(sink)
        , m_rolling(model.hasRollingSpring()) {
        m_batch.clear();
    }

    [[gnu::always_inline]] void operator()(PairOverlap const& p, std::uint8_t& hint) {
        ContactHistory& history = m_ps.pairHistory(p.i);
        std::size_t const before = history.size();
        Uid const partner = m_ps.uid(p.j);
        bool again = false;
        HistoryEntry* e = &history.touch(partner, m_stamp, hint, again);
        HistoryEntry* r = touchRolling(history, partner, e, hint);
        // An insertion moves the entries of p.i that earlier pairs of the batch may hold (none
        // if the history was empty: entries are not removed during a pass).
        m_moved = m_moved || (before != 0 && history.size() != before);
        if (again || m_batch.full()) {
            finish();
            e = &history.touch(partner, m_stamp, hint);
            r = m_rolling ? history.find(rollingKey(partner)) : nullptr;
        }
        m_batch.add(p, *e, hint, r);
    }
    void operator()(Contact const& c, std::uint8_t& hint) { (*this)(PairOverlap::of(c), hint); }
    /// The same for an overlapping pair whose spring `kept` lives beside the neighbour list
    /// (ContactDetector, "Springs kept beside the list"; without model C's rolling spring):
    /// stamped by finish(), as the history's entry would be.
    [[gnu::always_inline]] void operator()(PairOverlap const& p, KeptSpring& kept) {
        if (m_batch.full())
            finish();
        m_batch.addKept(p.i, p.j, p.shiftJ, kept, m_stamp);
    }
    void operator()(Contact const& c, KeptSpring& kept) { (*this)(PairOverlap::of(c), kept); }
    /// The same for the overlapping pairs `hits` of a block of kept pairs in one image
    /// (SpringDashpotBatch::addKeptHits), in the order of their bits.
    [[gnu::always_inline]] void keptHits(std::uint32_t const* i, std::uint32_t const* j,
                                         std::uint32_t const* at, std::uint64_t hits,
                                         KeptSpring* springs) {
        while ((hits = m_batch.addKeptHits(i, j, at, hits, springs, m_stamp)) != 0)
            finish();
    }
    /// The pass (ContactHistory stamp) this evaluates.
    [[nodiscard]] std::uint32_t pass() const { return m_stamp; }

    /// Evaluates what is gathered and hands it to the sink.
    [[gnu::noinline]] void finish() {
        SpringDashpotBatch& batch = m_batch;
        batch.evaluate(m_ps, m_model, m_dt);
        // The sink and the uids in locals: the shares' stores are Eigen packets, which may
        // alias anything, so members read through `this` would be loaded again after each.
        Sink sink = m_sink;
        Uid const* const uid = m_ps.uids().data();
        std::size_t const n = batch.size();
        for (std::size_t k = 0; k < n; ++k) {
            std::size_t const i = batch.i(k), j = batch.j(k);
            if (KeptSpring* kept = batch.kept(k)) {
                kept->spring = batch.spring(k);
                kept->stamp = m_stamp; // touched (its spring entered the lanes as the touch's)
            } else {
                HistoryEntry* e = batch.entry(k);
                HistoryEntry* r = batch.rollingEntry(k);
                if (m_moved) { // found again through the hint, or by search
                    std::uint8_t hint = batch.hint(k);
                    e = &m_ps.pairHistory(i).touch(m_ps.uid(j), m_stamp, hint);
                    r = m_rolling ? m_ps.pairHistory(i).find(rollingKey(m_ps.uid(j))) : nullptr;
                }
                e->spring = batch.spring(k);
                if (r)
                    r->spring = batch.rollingSpring(k);
            }
            core::Vec3 const f = batch.force(k);
            sink(j, uid[i], f, batch.torqueJ(k));
            sink(i, uid[j], core::Vec3(-f), core::Vec3(-batch.torqueI(k)));
        }
        batch.clear();
        m_moved = false;
    }

private:
    /// With model C, touches the pair's rolling entry (evaluatePair's withSprings: stamped,
    /// restarted from zero if the previous pass did not touch it); its insertion may move `e`,
    /// found again through the hint. nullptr without model C.
    [[gnu::always_inline]] HistoryEntry* touchRolling(ContactHistory& history, Uid partner,
                                                      HistoryEntry*& e, std::uint8_t& hint) {
        if (!m_rolling)
            return nullptr;
        std::size_t const size = history.size();
        HistoryEntry* r = &history.touch(rollingKey(partner), m_stamp);
        if (history.size() != size) {
            e = &history.touch(partner, m_stamp, hint);
            r = history.find(rollingKey(partner));
        }
        return r;
    }

    ParticleStorage& m_ps;
    SpringDashpot const& m_model;
    double m_dt;
    std::uint32_t m_stamp;
    SpringDashpotBatch& m_batch;
    Sink& m_sink;
    bool m_rolling;       ///< model C somewhere: every pair's rolling entry is touched
    bool m_moved = false; ///< some history of the batch's pairs got an entry since it started
};

/// The spring-dashpot's batch kernel (ContactState.hpp, BatchKernel): the contact loop
/// evaluates its pairs with BatchedSpringDashpot, then its wall contacts with
/// SpringDashpotWallBatch.
template <>
struct BatchKernel<SpringDashpot> {
    using Workspace = SpringDashpotBatch;
    using Walls = SpringDashpotWallBatch;
    template <class Sink>
    using Pairs = BatchedSpringDashpot<Sink>;
};

} // namespace regolith::particles
