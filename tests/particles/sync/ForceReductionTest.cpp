// Force reduction through the synchronisation: a dense gas is stepped with velocity Verlet,
// contacts detected and evaluated per block (some on shadows, whose forces and spring history
// must reach their masters), and the masters' forces, torques and states are compared with a
// single-block run of the same gas on one rank: within rounding in plain mode, bit for bit in
// reproducible mode, for every layout, method and rank count.
#include "core/mpi/Buffer.hpp"
#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/integration/VelocityVerlet.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::ReduceOp;

namespace {

struct MasterState {
    Uid uid = kInvalidUid;
    Vec3 position, velocity, force, torque;
};

SpringDashpot model() {
    LinearContactParams p;
    p.stiffness = 200.0;
    p.tangentialStiffness = 200.0 * 2.0 / 7.0;
    p.restitution = 0.8;
    p.friction = 0.5;
    return SpringDashpot{MaterialTable<LinearContactParams>(1, p)};
}

/// Every master of every rank, sorted by uid, on every rank. COLLECTIVE.
std::vector<MasterState> gatherMasters(LocalParticles const& local, Comm const& comm) {
    regolith::core::SendBuffer out;
    for (BlockParticles const& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) {
            ParticleStorage const& ps = bp.particles;
            out << ps.uid(i) << ps.position(i) << ps.velocity(i) << ps.force(i) << ps.torque(i);
        });
    std::string all;
    for (std::string const& s :
         comm.gatherStrings({reinterpret_cast<char const*>(out.data()), out.size()}, 0))
        all += s;
    comm.broadcast(all, 0);
    std::vector<std::byte> bytes(all.size());
    if (!all.empty())
        std::memcpy(bytes.data(), all.data(), all.size());
    regolith::core::RecvBuffer in(std::move(bytes));
    std::vector<MasterState> masters;
    while (!in.exhausted()) {
        MasterState& m = masters.emplace_back();
        in >> m.uid >> m.position >> m.velocity >> m.force >> m.torque;
    }
    std::sort(masters.begin(), masters.end(),
              [](MasterState const& a, MasterState const& b) { return a.uid < b.uid; });
    return masters;
}

struct Outcome {
    std::vector<MasterState> masters;
    std::uint64_t shadowContacts = 0; ///< contacts evaluated with a shadow participant, all steps
};

/// The DEM loop of docs/design.md ("The time step") on `spec` over `comm`: set-up forces, then
/// `steps` steps.
Outcome run(Comm const& comm, domain::ForestSpec const& spec, SyncConfig config,
            std::vector<ParticleInit> const& gas, int steps) {
    domain::BlockForest const forest(comm, spec);
    LocalParticles local(forest);
    ParticleSync sync(comm, forest, config);
    addAll(local, comm, gas);
    sync.requireNnsApplicable(local);
    sync.syncUntilConverged(local);
    PeriodicFrame const frame(forest);
    SpringDashpot const contactModel = model();
    VelocityVerlet const integrator;
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    std::vector<std::vector<ForceRecord>> records(local.blocks().size());
    double const dt = 2e-3;
    Vec3 const g(0.0, 0.0, -1.0);
    Outcome o;
    auto forces = [&](std::uint32_t stamp) {
        auto blocks = local.blocks();
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            ParticleStorage& ps = blocks[b].particles;
            ps.resetForces();
            detector.detect(ps, walls, blocks[b].block->aabb, frame, contacts);
            for (Contact const& c : contacts.pairs)
                o.shadowContacts += ps.flags(c.i).isShadow() || ps.flags(c.j).isShadow() ? 1 : 0;
            if (config.reproducible)
                evaluateContactsRecorded(ps, walls, contacts, contactModel, dt, stamp, records[b]);
            else
                evaluateContacts(ps, walls, contacts, contactModel, dt, stamp);
        }
        if (config.reproducible)
            sync.reduceForces(local, records, stamp);
        else
            sync.reduceForces(local, stamp);
    };
    forces(0);
    for (int step = 1; step <= steps; ++step) {
        for (BlockParticles& bp : local.blocks())
            integrator.preForce(bp.particles, dt, g);
        sync.sync(local);
        auto const v = checkSyncInvariants(local, comm, true); // before postForce moves on
        EXPECT_TRUE(v.empty()) << "step " << step << joined(v);
        forces(static_cast<std::uint32_t>(step));
        for (BlockParticles& bp : local.blocks())
            integrator.postForce(bp.particles, dt, g);
    }
    o.masters = gatherMasters(local, comm);
    o.shadowContacts = comm.allReduce(o.shadowContacts, ReduceOp::Sum);
    return o;
}

void compare(Outcome const& got, Outcome const& ref, bool bitwise, std::string const& where) {
    ASSERT_EQ(got.masters.size(), ref.masters.size()) << where;
    double scale = 0.0;
    for (MasterState const& m : ref.masters)
        scale = std::max(scale, m.force.norm());
    std::size_t mismatches = 0;
    for (std::size_t k = 0; k < ref.masters.size(); ++k) {
        MasterState const& a = got.masters[k];
        MasterState const& b = ref.masters[k];
        EXPECT_EQ(a.uid, b.uid) << where;
        bool same = false;
        if (bitwise) {
            same = sameBits(a.position, b.position) && sameBits(a.velocity, b.velocity) &&
                   sameBits(a.force, b.force) && sameBits(a.torque, b.torque);
        } else {
            // Only the summation order differs: rounding of a few ulps of the largest force,
            // carried through a few steps.
            double const tol = 1e-9 * (1.0 + scale);
            same = (a.force - b.force).norm() <= tol && (a.torque - b.torque).norm() <= tol &&
                   (a.position - b.position).norm() <= 1e-9 &&
                   (a.velocity - b.velocity).norm() <= 1e-9;
        }
        if (!same && ++mismatches <= 5) {
            ADD_FAILURE() << where << ": uid " << a.uid << " force (" << a.force.transpose()
                          << ") vs single block (" << b.force.transpose() << ")";
        }
    }
    EXPECT_EQ(mismatches, 0U) << where;
}

void reduction(bool reproducible) {
    Comm world;
    Comm self(MPI_COMM_SELF);
    AABB const domain{Vec3::Zero(), Vec3(6, 6, 6)};
    // ~20 % volume fraction placed at random: many overlapping pairs, also across blocks.
    auto const gas = randomGas(domain, 150, 0.3, 0.5, 1.0, 8);
    for (bool periodic : {false, true}) {
        SyncConfig const single{SyncMethod::Hybrid, reproducible};
        Outcome const ref = run(
            self, forestSpec(domain.min, domain.max, {1, 1, 1}, allAxes(periodic)), single, gas, 6);
        if (periodic) {
            EXPECT_EQ(ref.masters.size(), gas.size());
        }
        for (std::array<int, 3> blocks :
             {std::array{2, 2, 2}, std::array{3, 3, 3}, std::array{4, 2, 1}})
            for (SyncMethod m :
                 {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
                std::ostringstream where;
                where << methodName(m) << " " << blocks[0] << "x" << blocks[1] << "x" << blocks[2]
                      << (periodic ? " periodic" : " open")
                      << (reproducible ? " reproducible" : " plain");
                Outcome const got =
                    run(world, forestSpec(domain.min, domain.max, blocks, allAxes(periodic)),
                        SyncConfig{m, reproducible}, gas, 6);
                EXPECT_GT(got.shadowContacts, 0U) << where.str();
                compare(got, ref, reproducible, where.str());
            }
    }
}

} // namespace

TEST(ForceReduction, PlainSumsMatchTheSingleBlockRun) {
    reduction(false);
}

TEST(ForceReduction, ReproducibleSumsAreBitwiseEqualForEveryLayout) {
    reduction(true);
}
