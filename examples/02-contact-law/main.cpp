// Tutorial 02: a contact law of one's own — Hertz elasticity with DMT adhesion — given to the
// time step from this file, and its pull-off force measured against the closed form.
//
// The law (Derjaguin, Muller & Toporov 1975): a Hertz spring with a constant adhesive pull
// while the grains touch, F_n = 4/3 E* sqrt(R*) delta^(3/2) - 2 pi w R*, with w the work of
// adhesion [energy / area], plus a normal dashpot. Two grains stick; one is fixed, the other is
// pulled away by a slowly growing force of our own; they part when the pull exceeds the
// adhesion, at F = 2 pi w R* (the DMT pull-off force). Run: ./02-contact-law [steps].
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "particles/kernels/ContactLaw.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>

using namespace regolith;
using core::Vec3;

namespace {

/// The law: every contact, one call. `s.penetration` > 0 is the overlap, `s.normal` points
/// from i to j, the force returned acts on j (i gets the opposite).
class HertzDmt final : public particles::ContactLaw {
public:
    HertzDmt(double effectiveModulus, double workOfAdhesion, double dampingRatio)
        : m_modulus(effectiveModulus)
        , m_work(workOfAdhesion)
        , m_damping(dampingRatio) {}

    particles::ContactResponse operator()(particles::ContactState const& s, Vec3& /*spring*/,
                                          Vec3& /*rolling*/, double /*dt*/) const override {
        double const r = s.effectiveRadius;
        double const elastic = 4.0 / 3.0 * m_modulus * std::sqrt(r) * std::pow(s.penetration, 1.5);
        double const adhesion = 2.0 * std::numbers::pi * m_work * r;
        // A dashpot on the tangent stiffness k = dF/d(delta) = 2 E* sqrt(R* delta).
        double const k = 2.0 * m_modulus * std::sqrt(r * s.penetration);
        double const vn = s.relativeVelocity.dot(s.normal);
        double const fn =
            elastic - adhesion - 2.0 * m_damping * std::sqrt(k * s.effectiveMass) * vn;
        return {fn * s.normal, Vec3::Zero()}; // frictionless: no tangential force, no couple
    }

    /// The period of small oscillations about the resting overlap: the time scale the step
    /// must resolve (the grains here have radius 0.5, so R* = 0.25).
    double contactTime(std::uint32_t, std::uint32_t, double effectiveMass) const override {
        double const r = 0.25;
        double const k = 2.0 * m_modulus * std::sqrt(r * restingOverlap(r));
        return std::numbers::pi * std::sqrt(effectiveMass / k);
    }

    [[nodiscard]] double pullOff(double effectiveRadius) const {
        return 2.0 * std::numbers::pi * m_work * effectiveRadius;
    }
    /// The overlap at which the Hertz force balances the adhesion.
    [[nodiscard]] double restingOverlap(double effectiveRadius) const {
        return std::pow(pullOff(effectiveRadius) /
                            (4.0 / 3.0 * m_modulus * std::sqrt(effectiveRadius)),
                        2.0 / 3.0);
    }

private:
    double m_modulus, m_work, m_damping;
};

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    core::Comm const world;
    long long const steps = argc > 1 ? std::atoll(argv[1]) : 20000;

    auto const law = std::make_shared<HertzDmt>(1.0e4, 1.0, 0.5);
    coupling::SimulationSetup setup;
    setup.domain.domain = core::AABB{Vec3::Constant(-4.0), Vec3::Constant(4.0)};
    setup.domain.rootBlocks = {2, 2, 2};
    setup.contact = particles::CustomContact(law); // the law, given to the step
    setup.dem.dt = 2e-3;
    coupling::Simulation sim(world, setup);

    // Two grains of radius 0.5 stuck together at the origin, at rest (the overlap where the
    // Hertz force balances the adhesion: a contact exists only while the grains overlap); the
    // left one held in place.
    double const mass = 4.0 / 3.0 * std::numbers::pi * 0.125;
    double const overlap = law->restingOverlap(0.25);
    double const fixedAt = -(0.5 - 0.5 * overlap);
    for (int side : {-1, 1}) {
        particles::ParticleInit p;
        p.uid = side < 0 ? 0 : 1;
        p.position = Vec3((0.5 - 0.5 * overlap) * side, 0.0, 0.0);
        p.radius = 0.5;
        p.mass = mass;
        if (side < 0)
            p.flags = particles::Flag::Fixed;
        sim.addGrain(p);
    }

    // Our force: on grain 1, along +x, growing linearly to 1.5x the pull-off over the run.
    double const pullOff = law->pullOff(0.25);
    double const rate = 1.5 * pullOff / (static_cast<double>(steps) * setup.dem.dt);
    sim.addBodyForces([&](particles::LocalParticles& grains) {
        for (particles::BlockParticles& block : grains.blocks())
            block.particles.forEachMaster([&](std::size_t i) {
                if (block.particles.uid(i) == 1)
                    block.particles.force(i).x() += rate * sim.time();
            });
    });
    // Our observer: the pull when the grains parted (their gap opened), every step.
    double parted = 0.0;
    sim.addObserver(1, [&](coupling::Simulation& s) {
        double x = 0.0;
        s.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
            if (g.uid(i) == 1)
                x = g.position(i).x();
        });
        x = s.comm().allReduce(x, core::ReduceOp::Sum);
        if (parted == 0.0 && x - fixedAt > 1.0) // centres a diameter apart: no overlap left
            parted = rate * s.time();
    });
    sim.start();
    sim.run(steps);

    double const error = std::abs(parted - pullOff) / pullOff;
    if (world.rank() == 0)
        std::printf("pull-off force: measured %.5f, DMT 2 pi w R* = %.5f (%.2f %% apart)\n", parted,
                    pullOff, 100.0 * error);
    return error < 0.01 ? 0 : 1;
}
