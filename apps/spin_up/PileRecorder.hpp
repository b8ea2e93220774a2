#pragma once
/// What the rubble-pile app adds to a run: the body forces of [spin_up] and [flyby] and an
/// observer recording the pile to a CSV file ([pile]). The pile's scales (its mass, centre,
/// bulk radius and critical spin omega_c) are measured in the first force computation after
/// pile.settle_steps steps, from the grains gathered in uid order, so the same bits feed the
/// forces on any rank count; a restart reads them back from the record (resume). The
/// recorder's clock counts the force computations (one at the start, one a step): the time
/// of the spin-up and of the fly-by's pass.
///
/// CSV (PileRecordFile.hpp): a first line with the reference, then the columns time, spin
/// (about the spin-up axis, z without [spin_up]) and spin / omega_c, the equivalent
/// ellipsoid's semi-axes a >= b >= c, the fraction of the initial mass shed (beyond
/// pile.radius initial bulk radii of the pile's centre, or gone from the domain), the largest
/// remnant's fraction and the number of clusters (friends-of-friends), the pile's centre, and
/// with [flyby] the perturber's distance in Roche radii.
#include "apps/spin_up/PileRecordFile.hpp"
#include "apps/spin_up/RubblePileSections.hpp"
#include "apps/spin_up/TidalFlyby.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>

namespace regolith::apps {

/// One record of the pile.
struct PileRecord {
    double time = 0.0;
    double spin = 0.0;
    std::array<double, 3> axes{0.0, 0.0, 0.0};
    double shedFraction = 0.0;
    double remnantFraction = 0.0;
    std::size_t clusters = 0;
};

class PileRecorder {
public:
    /// `G` the self-gravity's constant, `dt` the time step. Opens nothing yet.
    PileRecorder(core::Comm const& comm, RubblePileScene scene, double G, double dt);
    ~PileRecorder();
    PileRecorder(PileRecorder const&) = delete;
    PileRecorder& operator=(PileRecorder const&) = delete;

    /// The body forces at the next force computation (none while the pile settles; the first
    /// after it measures the pile, checks the spin-up rate and opens the CSV: COLLECTIVE,
    /// InputError on every rank).
    void addForces(particles::LocalParticles& grains);
    /// Measures and records the pile (rank 0 writes the row); nullopt while it settles.
    /// COLLECTIVE.
    std::optional<PileRecord> record(particles::LocalParticles const& grains);
    /// Instead of the first force computation's measure, on a restart after `stepsDone` steps:
    /// the pile's scales, centre and peak spin from the record written so far (pile.file),
    /// whose rows after the checkpoint are dropped, to be written again. InputError (every
    /// rank) if the record is missing (naming where the restarted `checkpoint`'s record
    /// probably is) or unreadable. COLLECTIVE.
    void resume(std::int64_t stepsDone, std::string const& checkpoint);

    /// Throws core::Error unless the force computations counted so far are those of
    /// `stepsDone` steps (the recorder's clock: time = force computations x dt).
    void requireStep(std::int64_t stepsDone) const;
    /// The last record made, if any.
    [[nodiscard]] std::optional<PileRecord> const& lastRecord() const { return m_last; }
    [[nodiscard]] std::int64_t recordEvery() const { return m_scene.pile.recordEvery; }
    [[nodiscard]] PileReference const& reference() const { return m_reference; }
    /// The spin / omega_c at the first record with mass shed; nullopt before.
    [[nodiscard]] std::optional<double> sheddingOnset() const { return m_onset; }
    /// The failure spin / omega_c: the highest spin recorded, once the spin has fallen 0.02
    /// omega_c below it (a pile spun up by a steady torque turns slower only when its mass moves
    /// outwards: it deforms or sheds); nullopt before.
    [[nodiscard]] std::optional<double> failureSpin() const;
    /// The fly-by's pass, once the pile is measured (with [flyby]).
    [[nodiscard]] HyperbolicPass const* pass() const { return m_pass.get(); }

private:
    void measureReference(particles::LocalParticles const& grains);
    /// What follows from the reference: the spin-up check, the fly-by's pass.
    void adoptReference();
    /// Opens pile.file on rank 0 ("w" or "a"); InputError on every rank if it cannot.
    void openRecord(char const* mode);
    /// Follows the peak spin (failureSpin).
    void track(double spin);
    [[nodiscard]] core::Vec3 axis() const;

    core::Comm const* m_comm;
    RubblePileScene m_scene;
    double m_G;
    double m_dt;
    std::int64_t m_forceCalls = 0;     ///< force computations so far (the first at time 0)
    [[nodiscard]] double time() const; ///< of the last force computation, from the settling
    PileReference m_reference;
    core::Vec3 m_centre = core::Vec3::Zero(); ///< the pile's, at the last record
    double m_rocheRadius = 0.0;
    double m_flybyGM = 0.0;
    std::unique_ptr<HyperbolicPass> m_pass;
    std::optional<double> m_onset;
    double m_peakSpin = 0.0; ///< the highest spin / omega_c recorded
    bool m_fellFromPeak = false;
    std::optional<PileRecord> m_last;
    std::FILE* m_csv = nullptr;
};

} // namespace regolith::apps
