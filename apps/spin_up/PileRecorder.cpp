#include "apps/spin_up/PileRecorder.hpp"

#include "apps/spin_up/PileMeasures.hpp"
#include "apps/spin_up/PileRecords.hpp"
#include "apps/spin_up/Remnants.hpp"
#include "apps/spin_up/SpinUpTorque.hpp"
#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <utility>

namespace regolith::apps {

using core::Vec3;

namespace {

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
    if (m_scene.spinUp)
        checkSpinUpRate(*m_scene.spinUp, m_reference.omegaC, m_dt);
    if (m_scene.flyby) {
        FlybySection const& f = *m_scene.flyby;
        m_rocheRadius = rocheRadius(f.mass, pile.bulkDensity());
        m_flybyGM = m_G * f.mass;
        m_pass = std::make_unique<HyperbolicPass>(m_G * (f.mass + pile.mass),
                                                  f.periapsis * m_rocheRadius, f.eccentricity,
                                                  f.startDistance * m_rocheRadius);
    }
    bool opened = true;
    if (m_comm->rank() == 0) {
        m_csv = std::fopen(m_scene.pile.file.c_str(), "w");
        opened = m_csv != nullptr;
    }
    if (!m_comm->allTrue(opened))
        throw core::InputError(
            fmt::format("pile.file = \"{}\": cannot create the file", m_scene.pile.file));
    if (m_csv) {
        std::fprintf(m_csv,
                     "# mass=%.17g bulk_radius=%.17g omega_c=%.17g roche_radius=%.17g\n"
                     "time,spin,spin_over_omega_c,axis_a,axis_b,axis_c,shed_fraction,"
                     "remnant_fraction,clusters%s\n",
                     m_reference.mass, m_reference.bulkRadius, m_reference.omegaC, m_rocheRadius,
                     m_pass ? ",perturber_distance" : "");
        std::fflush(m_csv);
    }
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
    double const spin = r.spin / m_reference.omegaC;
    if (!m_onset && r.shedFraction > 0.0)
        m_onset = spin;
    if (!m_fellFromPeak) {
        m_peakSpin = std::max(m_peakSpin, spin);
        m_fellFromPeak = spin < m_peakSpin - kFailureDrop;
    }
    if (m_csv) {
        std::fprintf(m_csv, "%.9g,%.9g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu", r.time, r.spin,
                     r.spin / m_reference.omegaC, r.axes[0], r.axes[1], r.axes[2], r.shedFraction,
                     r.remnantFraction, r.clusters);
        if (m_pass)
            std::fprintf(m_csv, ",%.6g",
                         (m_pass->position(time) - (m_centre - m_reference.centre)).norm() /
                             m_rocheRadius);
        std::fprintf(m_csv, "\n");
        std::fflush(m_csv); // a long run can be watched
    }
    return r;
}

} // namespace regolith::apps
