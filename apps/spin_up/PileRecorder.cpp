#include "apps/spin_up/PileRecorder.hpp"

#include "apps/spin_up/PileMeasures.hpp"
#include "apps/spin_up/PileRecordFile.hpp"
#include "apps/spin_up/PileRecords.hpp"
#include "apps/spin_up/Remnants.hpp"
#include "apps/spin_up/SpinUpTorque.hpp"
#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>

namespace regolith::apps {

using core::Vec3;

namespace {

/// What rank 0 broadcasts for a record it cannot find (a record starts with '#').
constexpr std::string_view kMissing = "(no such file)";

/// The drop below the peak spin [omega_c] that marks the peak as the failure spin.
constexpr double kFailureDrop = 0.02;

} // namespace

PileRecorder::PileRecorder(core::Comm const& comm, RubblePileScene scene, double G, double dt)
    : m_comm(&comm)
    , m_scene(std::move(scene))
    , m_G(G)
    , m_dt(dt) {}

PileRecorder::~PileRecorder() {
    if (m_csv)
        std::fclose(m_csv);
}

Vec3 PileRecorder::axis() const {
    return m_scene.spinUp ? m_scene.spinUp->axis : Vec3::UnitZ();
}

void PileRecorder::measureReference(particles::LocalParticles const& grains) {
    std::vector<MasterRecord> const all = gatherMastersByUid(*m_comm, grains);
    double const everywhere = std::numeric_limits<double>::infinity();
    PileMeasures const pile = measurePile(all, Vec3::Zero(), everywhere, axis());
    if (!(pile.mass > 0.0))
        throw core::InputError("the rubble pile has no grains: expected [[particles]] entries");
    m_reference.mass = pile.mass;
    m_reference.centre = pile.centre;
    m_reference.bulkRadius = pile.bulkRadius();
    m_reference.omegaC = pile.criticalSpin(m_G);
    m_reference.spin = pile.spin;
    double radii = 0.0;
    for (MasterRecord const& g : all)
        radii += g.radius;
    m_reference.meanGrainRadius = radii / static_cast<double>(all.size());
    m_centre = pile.centre;
    adoptReference();
    openRecord("w");
    if (m_csv) {
        PileReference const& r = m_reference;
        std::fprintf(m_csv,
                     "# mass=%.17g bulk_radius=%.17g omega_c=%.17g spin=%.17g centre_x=%.17g "
                     "centre_y=%.17g centre_z=%.17g mean_grain_radius=%.17g\n"
                     "time,spin,spin_over_omega_c,axis_a,axis_b,axis_c,shed_fraction,"
                     "remnant_fraction,clusters,centre_x,centre_y,centre_z%s\n",
                     r.mass, r.bulkRadius, r.omegaC, r.spin, r.centre.x(), r.centre.y(),
                     r.centre.z(), r.meanGrainRadius, m_pass ? ",perturber_distance" : "");
        std::fflush(m_csv);
    }
}

void PileRecorder::adoptReference() {
    if (m_scene.spinUp)
        checkSpinUpRate(*m_scene.spinUp, m_reference.omegaC, m_dt);
    if (m_scene.flyby) {
        FlybySection const& f = *m_scene.flyby;
        double const density =
            m_reference.mass / (4.0 / 3.0 * std::numbers::pi * std::pow(m_reference.bulkRadius, 3));
        m_rocheRadius = rocheRadius(f.mass, density);
        m_flybyGM = m_G * f.mass;
        m_pass = std::make_unique<HyperbolicPass>(m_G * (f.mass + m_reference.mass),
                                                  f.periapsis * m_rocheRadius, f.eccentricity,
                                                  f.startDistance * m_rocheRadius);
    }
}

void PileRecorder::openRecord(char const* mode) {
    bool opened = true;
    if (m_comm->rank() == 0) {
        m_csv = std::fopen(m_scene.pile.file.c_str(), mode);
        opened = m_csv != nullptr;
    }
    if (!m_comm->allTrue(opened))
        throw core::InputError(
            fmt::format("pile.file = \"{}\": cannot write the file", m_scene.pile.file));
}

void PileRecorder::resume(std::int64_t stepsDone, std::string const& checkpoint) {
    m_forceCalls = stepsDone + 1; // the next force computation is the next step's
    if (stepsDone < m_scene.pile.settleSteps)
        return;
    // The record so far, from rank 0: the reference from its first line, the rows up to the
    // checkpoint kept (the rest is written again), the last one's pile centre.
    std::string text;
    if (m_comm->rank() == 0)
        text = std::filesystem::exists(m_scene.pile.file) ? readPileRecord(m_scene.pile.file)
                                                          : std::string(kMissing);
    m_comm->broadcast(text, 0);
    if (text == kMissing) {
        std::filesystem::path const beside = std::filesystem::path(checkpoint).parent_path() /
                                             std::filesystem::path(m_scene.pile.file).filename();
        throw core::InputError(fmt::format(
            "pile.file = \"{}\": no such file; a restart continues the record of the run being "
            "restarted: copy it there (probably {}, beside the checkpoint)",
            m_scene.pile.file, beside.string()));
    }
    double const until = static_cast<double>(stepsDone - m_scene.pile.settleSteps) * m_dt;
    ResumedRecord const resumed = resumeRecord(text, until, m_scene.pile.file);
    m_reference = resumed.reference;
    m_centre = resumed.centre;
    for (double spin : resumed.spins)
        track(spin);
    m_onset = resumed.onset;
    adoptReference();
    if (m_comm->rank() == 0) {
        std::FILE* out = std::fopen(m_scene.pile.file.c_str(), "w");
        if (out) {
            std::fputs(resumed.kept.c_str(), out);
            std::fclose(out);
        }
    }
    openRecord("a");
}

double PileRecorder::time() const {
    return static_cast<double>(m_forceCalls - 1 - m_scene.pile.settleSteps) * m_dt;
}

void PileRecorder::addForces(particles::LocalParticles& grains) {
    if (m_forceCalls++ < m_scene.pile.settleSteps)
        return;
    if (m_reference.mass == 0.0)
        measureReference(grains);
    double const time = this->time();
    double const reach = m_scene.pile.radius * m_reference.bulkRadius;
    if (m_scene.spinUp) {
        SpinUpSection const& s = *m_scene.spinUp;
        double const alpha = s.rate * m_reference.omegaC * m_reference.omegaC;
        if (m_reference.spin + alpha * time < s.finalSpin * m_reference.omegaC)
            addSpinUpTorque(grains, m_centre, s.axis, alpha, reach);
    }
    if (m_pass)
        addTidalForce(grains, m_reference.centre, m_reference.centre + m_pass->position(time),
                      m_flybyGM);
}

void PileRecorder::requireStep(std::int64_t stepsDone) const {
    if (m_forceCalls != stepsDone + 1)
        throw core::Error(fmt::format("the rubble-pile recorder counted {} force computations "
                                      "after {} steps: its clock is off",
                                      m_forceCalls, stepsDone));
}

void PileRecorder::track(double spin) {
    if (m_fellFromPeak)
        return;
    m_peakSpin = std::max(m_peakSpin, spin);
    m_fellFromPeak = spin < m_peakSpin - kFailureDrop;
}

std::optional<double> PileRecorder::failureSpin() const {
    return m_fellFromPeak ? std::optional<double>(m_peakSpin) : std::nullopt;
}

std::optional<PileRecord> PileRecorder::record(particles::LocalParticles const& grains) {
    if (m_reference.mass == 0.0)
        return std::nullopt;
    double const time = this->time();
    std::vector<MasterRecord> const all = gatherMastersByUid(*m_comm, grains);
    double const radius = m_scene.pile.radius * m_reference.bulkRadius;
    PileMeasures const p = measurePile(all, m_centre, radius, axis());
    Remnant const remnant = largestRemnant(all, m_scene.pile.linkGap * m_reference.meanGrainRadius);
    if (p.mass > 0.0)
        m_centre = p.centre;
    PileRecord r;
    r.time = time;
    r.spin = p.spin;
    r.axes = p.axes;
    r.shedFraction = std::max(0.0, 1.0 - p.mass / m_reference.mass);
    r.remnantFraction = remnant.mass / m_reference.mass;
    r.clusters = remnant.clusters;
    if (!m_onset && r.shedFraction > 0.0)
        m_onset = r.spin / m_reference.omegaC;
    track(r.spin / m_reference.omegaC);
    if (m_csv) {
        std::fprintf(m_csv, "%.9g,%.9g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%.17g,%.17g,%.17g", r.time,
                     r.spin, r.spin / m_reference.omegaC, r.axes[0], r.axes[1], r.axes[2],
                     r.shedFraction, r.remnantFraction, r.clusters, m_centre.x(), m_centre.y(),
                     m_centre.z());
        if (m_pass)
            std::fprintf(m_csv, ",%.6g",
                         (m_pass->position(time) - (m_centre - m_reference.centre)).norm() /
                             m_rocheRadius);
        std::fprintf(m_csv, "\n");
        std::fflush(m_csv); // a long run can be watched
    }
    m_last = r;
    return r;
}

} // namespace regolith::apps
