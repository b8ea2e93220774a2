// Bad initial state and bad time step: each is a core::InputError naming the uid.
#include "core/mpi/Comm.hpp"
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/validation/ParticleValidation.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::AABB;
using regolith::core::Comm;
using regolith::core::InputError;

namespace {

/// A valid 3 x 3 x 3 lattice of radius-0.4 grains, uids 100..126, in the domain [0, 3]^3.
ParticleStorage validSet() {
    ParticleStorage ps;
    Uid uid = 100;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                ps.add(sphere(uid++, Vec3(i + 0.5, j + 0.5, k + 0.5), 0.4, 1.0));
    return ps;
}

ValidationOptions options() {
    ValidationOptions o;
    o.domain = AABB{Vec3::Zero(), Vec3::Constant(3.0)};
    return o;
}

/// Expects validateParticles to throw an InputError whose message contains every `needle`.
void expectRejected(ParticleStorage const& ps, ValidationOptions const& o,
                    std::initializer_list<std::string> needles) {
    Comm world;
    try {
        validateParticles(world, ps, o);
        ADD_FAILURE() << "no error for " << *needles.begin();
    } catch (InputError const& e) {
        for (auto const& n : needles)
            EXPECT_NE(std::string(e.what()).find(n), std::string::npos)
                << "'" << n << "' not in: " << e.what();
    }
}

} // namespace

TEST(Validation, AValidSetPasses) {
    Comm world;
    EXPECT_NO_THROW(validateParticles(world, validSet(), options()));
    EXPECT_FALSE(findInvalidParticle(ParticleStorage{}, options()).has_value());
}

TEST(Validation, BadRadiusMassOrDensityNamesTheUid) {
    double const nan = std::numeric_limits<double>::quiet_NaN();
    for (double bad : {0.0, -0.4, nan}) {
        ParticleStorage ps = validSet();
        ps.setRadius(ps.find(113), bad);
        expectRejected(ps, options(), {"uid 113", "radius"});
        ParticleStorage pm = validSet();
        pm.setMass(pm.find(107), bad);
        expectRejected(pm, options(), {"uid 107", "mass"});
    }
    // Two problems: the smaller uid is reported.
    ParticleStorage ps = validSet();
    ps.setMass(ps.find(120), -1.0);
    ps.setRadius(ps.find(104), 0.0);
    expectRejected(ps, options(), {"uid 104"});
    // A density that overflows (mass finite, volume tiny) is caught as such.
    ParticleStorage pd = validSet();
    pd.setRadius(pd.find(101), 1e-120);
    expectRejected(pd, options(), {"uid 101", "density"});
    // Generators check a scene's density before making particles.
    EXPECT_THROW(requirePositiveFinite(-2.0, "particles[0].density"), InputError);
    EXPECT_THROW(requirePositiveFinite(nan, "particles[0].density"), InputError);
    EXPECT_NO_THROW(requirePositiveFinite(2.0, "particles[0].density"));
}

TEST(Validation, OverlappingGrainsNameBothUids) {
    ParticleStorage ps = validSet();
    ps.position(ps.find(110)) = ps.position(ps.find(111)) - Vec3(0, 0, 0.7); // overlap 0.1
    expectRejected(ps, options(), {"uid 110", "uid 111", "overlap"});
    // Within the tolerance (1e-6 of the radius) is accepted: touching lattices round off.
    ParticleStorage touching = validSet();
    touching.position(touching.find(110)) =
        touching.position(touching.find(111)) - Vec3(0, 0, 0.8 - 1e-9);
    Comm world;
    EXPECT_NO_THROW(validateParticles(world, touching, options()));
}

TEST(Validation, OutsideTheDomainUnlessPeriodic) {
    ParticleStorage ps = validSet();
    ps.position(ps.find(125)).y() = 3.5;
    expectRejected(ps, options(), {"uid 125", "outside the domain", "axis y"});
    ValidationOptions periodic = options();
    periodic.periodic[1] = true;
    Comm world;
    EXPECT_NO_THROW(validateParticles(world, ps, periodic));
    // Shadows may be periodic images outside the domain; only masters are checked.
    ps.setFlags(ps.find(125), Flag::Shadow);
    EXPECT_NO_THROW(validateParticles(world, ps, options()));
    // Positions that are not finite, and unknown material types.
    ParticleStorage pn = validSet();
    pn.position(pn.find(102)).x() = std::numeric_limits<double>::infinity();
    expectRejected(pn, options(), {"uid 102", "not finite"});
    ParticleStorage pt = validSet();
    pt.setType(pt.find(103), 5);
    ValidationOptions typed = options();
    typed.numTypes = 2;
    expectRejected(pt, typed, {"uid 103", "type 5"});
}

TEST(TimeStepGuard, MessageNamesDtContactTimeStiffnessMassAndUid) {
    LinearContactParams p;
    p.stiffness = 2e4;
    p.restitution = 0.7;
    MaterialTable<LinearContactParams> table(2, p);
    LinearContactParams stiff = p;
    stiff.stiffness = 8e4;
    table.set(0, 1, stiff); // the mixed pair is stiffer
    SpringDashpot const model(table);
    ParticleStorage ps = validSet();
    ps.setMass(ps.find(111), 0.25); // lightest of type 0
    ps.setType(ps.find(120), 1);
    ps.setMass(ps.find(120), 0.5); // only one of type 1
    ps.setMass(ps.find(121), 0.01);
    ps.setFlags(ps.find(121), Flag::Fixed); // fixed: does not count
    ContactTimeEstimate const e = estimateContactTime(ps, model);
    // Candidates: (0,0) k = 2e4, m_eff = 0.125; (0,1) k = 8e4, m_eff = 1/6; (1,1) 2e4, 0.25.
    double const t00 = SpringDashpot::undampedContactTime(p, 0.125);
    double const t01 = SpringDashpot::undampedContactTime(stiff, 0.25 * 0.5 / 0.75);
    ASSERT_LT(t01, t00);
    EXPECT_NEAR(e.contactTime, t01, 1e-15);
    EXPECT_EQ(e.uid, 111U);
    EXPECT_EQ(e.mass, 0.25);
    EXPECT_EQ(e.parameterValue, 8e4);
    try {
        checkTimeStep(e.contactTime / 5, e, false);
        ADD_FAILURE() << "dt = t_c / 5 was accepted";
    } catch (InputError const& err) {
        std::string const m = err.what();
        for (char const* needle :
             {"time.dt = ", "exceeds t_c/10 = ", "t_c = ", "contact.stiffness = 80000",
              "smallest mass 0.25", "uid 111", "time.allow_unstable = true"})
            EXPECT_NE(m.find(needle), std::string::npos) << needle << " not in: " << m;
    }
    EXPECT_THROW(checkTimeStep(0.0, e, true), InputError);
    EXPECT_THROW(checkTimeStep(std::nan(""), e, true), InputError);
    // Hertz: t_c at the stated impact velocity from the lightest grain's mass and radius.
    auto const hp = HertzMindlinParams::fromMaterials(1e7, 0.25, 1e7, 0.25, 0.9, 0.5);
    HertzMindlin const hertz{MaterialTable<HertzMindlinParams>(1, hp)};
    ParticleStorage one = validSet();
    one.setMass(one.find(105), 0.5);
    ContactTimeEstimate const h = estimateContactTime(one, hertz, 2.0);
    EXPECT_NEAR(h.contactTime, HertzMindlin::contactTime(hp, 0.25, 0.2, 2.0), 1e-15);
    EXPECT_EQ(h.uid, 105U);
    EXPECT_THROW((void)estimateContactTime(one, hertz, 0.0), InputError);
    // A particle type outside the table is an input error naming the uid.
    one.setType(one.find(106), 3);
    try {
        (void)estimateContactTime(one, hertz, 2.0);
        ADD_FAILURE() << "type 3 accepted";
    } catch (InputError const& err) {
        EXPECT_NE(std::string(err.what()).find("uid 106"), std::string::npos);
    }
}

TEST(ContactModels, RejectOutOfRangeParameters) {
    LinearContactParams p;
    p.stiffness = 1.0;
    auto make = [](LinearContactParams q) {
        return SpringDashpot(MaterialTable<LinearContactParams>(2, q));
    };
    EXPECT_NO_THROW(make(p));
    for (auto bad : std::initializer_list<std::function<void(LinearContactParams&)>>{
             [](auto& q) { q.stiffness = 0; }, [](auto& q) { q.restitution = 0; },
             [](auto& q) { q.restitution = 1.1; }, [](auto& q) { q.friction = -1; },
             [](auto& q) { q.tangentialStiffness = std::nan(""); }}) {
        LinearContactParams q = p;
        bad(q);
        EXPECT_THROW(make(q), InputError);
    }
    EXPECT_THROW((void)HertzMindlinParams::fromMaterials(-1, 0.3, 1, 0.3, 1, 0), InputError);
    EXPECT_THROW((void)HertzMindlinParams::fromMaterials(1, 0.6, 1, 0.3, 1, 0), InputError);
    MaterialTable<LinearContactParams> t(2, p);
    EXPECT_THROW(t.set(0, 2, p), InputError);
}
