// Grain fields of one's own (particles/storage/GrainFields.hpp): declared once, they travel
// with the grains through the synchronisation (shadows read their master's values, migrating
// masters keep theirs), and checkpoints, VTK output and the dump write them as named columns.
// Its own test program: the declarations are process-wide.
#include "apps/common/StateDump.hpp"
#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/vtk/VtkPieces.hpp"
#include "particles/storage/GrainFields.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <unistd.h>
#include <vector>

using namespace regolith;
using core::Vec3;

namespace {

particles::GrainFieldId temperature() {
    static particles::GrainFieldId const id =
        particles::declareGrainField({"temperature", 1, "K", "grain temperature"});
    return id;
}

particles::GrainFieldId heatFlux() {
    static particles::GrainFieldId const id =
        particles::declareGrainField({"heat_flux", 3, "W/m^2", "heat flux"});
    return id;
}

/// The values a grain's fields get at `step`.
double temperatureOf(particles::Uid uid, std::int64_t step) {
    return 300.0 + static_cast<double>(uid) + 1e-3 * static_cast<double>(step);
}
Vec3 fluxOf(particles::Uid uid, std::int64_t step) {
    return {static_cast<double>(uid), static_cast<double>(step), -static_cast<double>(uid)};
}

/// A periodic gas of 4 x 4 x 4 grains crossing 3 x 3 x 3 blocks (every grain has shadows, many
/// masters change block and rank).
coupling::SimulationSetup gasSetup() {
    coupling::SimulationSetup s;
    s.domain.domain = core::AABB{Vec3::Zero(), Vec3::Constant(6.0)};
    s.domain.rootBlocks = {3, 3, 3};
    s.domain.periodic = {true, true, true};
    particles::LinearContactParams p;
    p.stiffness = 1000.0;
    p.tangentialStiffness = 2.0 / 7.0 * p.stiffness;
    p.restitution = 0.9;
    s.contact =
        particles::SpringDashpot(particles::MaterialTable<particles::LinearContactParams>(1, p));
    s.dem.dt = 0.002;
    return s;
}

void addGas(coupling::Simulation& sim) {
    particles::Uid uid = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k, ++uid) {
                particles::ParticleInit p;
                p.uid = uid;
                p.position = Vec3(0.75 + 1.5 * i, 0.75 + 1.5 * j, 0.75 + 1.5 * k);
                p.velocity = Vec3(2.0 * ((i + k) % 3 - 1), 1.5 * ((j + 2 * k) % 3 - 1), 1.0);
                p.radius = 0.5;
                p.mass = 4.0 / 3.0 * std::numbers::pi * 0.125;
                sim.addGrain(p);
            }
}

} // namespace

TEST(GrainFields, DeclarationsAreCheckedAndRepeatable) {
    particles::GrainFieldId const t = temperature();
    particles::GrainFieldId const again =
        particles::declareGrainField({"temperature", 1, "K", "declared twice"});
    EXPECT_EQ(again.offset, t.offset);
    EXPECT_THROW(particles::declareGrainField({"a b", 1, "1", ""}), core::Error);
    EXPECT_THROW(particles::declareGrainField({"position", 3, "length", ""}), core::Error);
    EXPECT_THROW(particles::declareGrainField({"moisture", 2, "1", ""}), core::Error);
    EXPECT_THROW(particles::declareGrainField({"temperature", 3, "K", ""}), core::Error);
}

TEST(GrainFields, ShadowsReadTheirMastersValuesWhileTheGrainsMove) {
    core::Comm const world;
    particles::GrainFieldId const t = temperature();
    particles::GrainFieldId const q = heatFlux();
    // One particle subdomain per block: shadows on every rank count, also on one rank.
    coupling::SimulationSetup setup = gasSetup();
    setup.subdomains = domain::Subdomains::Blocks;
    coupling::Simulation sim(world, setup);
    addGas(sim);
    std::int64_t lastSet = -1;
    // Every 20 steps the masters get new values; 7 steps later every copy must hold them.
    sim.addObserver(20, [&](coupling::Simulation& s) {
        s.forEachGrain([&](particles::ParticleStorage& g, std::size_t i) {
            g.field(t, i) = temperatureOf(g.uid(i), s.stepsDone());
            for (std::size_t c = 0; c < 3; ++c)
                g.field(q, i, c) = fluxOf(g.uid(i), s.stepsDone())[static_cast<Eigen::Index>(c)];
        });
        lastSet = s.stepsDone();
    });
    long long checkedShadows = 0, wrong = 0;
    sim.addObserver([](std::int64_t step) { return step > 20 && step % 20 == 7; },
                    [&](coupling::Simulation& s) {
                        for (particles::BlockParticles const& b : s.grains().blocks())
                            b.particles.forEach([&](std::size_t i) {
                                particles::ParticleStorage const& g = b.particles;
                                checkedShadows += g.flags(i).isShadow() ? 1 : 0;
                                Vec3 const flux(g.field(q, i, 0), g.field(q, i, 1),
                                                g.field(q, i, 2));
                                if (g.field(t, i) != temperatureOf(g.uid(i), lastSet) ||
                                    flux != fluxOf(g.uid(i), lastSet))
                                    ++wrong;
                            });
                    },
                    {});
    sim.start();
    sim.run(200);
    EXPECT_EQ(world.allReduce(wrong, core::ReduceOp::Sum), 0);
    EXPECT_GT(world.allReduce(checkedShadows, core::ReduceOp::Sum), 0);
}

TEST(GrainFields, CheckpointsAndTheDumpWriteThemAsNamedColumns) {
    core::Comm const world;
    particles::GrainFieldId const t = temperature();
    particles::GrainFieldId const q = heatFlux();
    coupling::Simulation sim(world, gasSetup());
    addGas(sim);
    sim.start();
    sim.forEachGrain([&](particles::ParticleStorage& g, std::size_t i) {
        g.field(t, i) = temperatureOf(g.uid(i), 5);
        g.field(q, i, 1) = -1.0 * static_cast<double>(g.uid(i));
    });
    // A checkpoint and back: the fields are stored and read as they were.
    std::string const path =
        (std::filesystem::temp_directory_path() /
         ("grain-fields-" +
          std::to_string(world.allReduce(static_cast<long long>(::getpid()), core::ReduceOp::Max)) +
          ".h5"))
            .string();
    io::CheckpointInfo info;
    info.dt = 0.002;
    std::vector<io::GrainState> const grains = io::collectMasters(sim.grains());
    (void)io::writeCheckpoint(world, path, info, grains);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    long long wrong = 0, read = 0;
    for (io::GrainState const& g : slice.grains) {
        ++read;
        ASSERT_EQ(g.fields.size(), 4u);
        if (g.fields[t.offset] != temperatureOf(g.uid, 5) ||
            g.fields[q.offset + 1] != -1.0 * static_cast<double>(g.uid) ||
            g.fields[q.offset] != 0.0)
            ++wrong;
    }
    EXPECT_EQ(world.allReduce(read, core::ReduceOp::Sum), 64);
    EXPECT_EQ(world.allReduce(wrong, core::ReduceOp::Sum), 0);
    world.barrier();
    if (world.rank() == 0)
        std::filesystem::remove(path);

    // VTK: a point-data array per field, after the built-in ones.
    std::vector<io::vtkxml::ArraySpec> const arrays = io::detail::particleArrays(false);
    ASSERT_GE(arrays.size(), 2u);
    EXPECT_EQ(arrays[arrays.size() - 2].name, "temperature");
    EXPECT_EQ(arrays.back().name, "heat_flux");
    EXPECT_EQ(arrays.back().components, 3);

    // The dump: the contract's columns, then one per component.
    apps::MasterRecord m;
    m.uid = 3;
    m.fields = {301.5, 1.0, 2.0, 3.0};
    std::string const csv = apps::dumpCsv(std::span(&m, 1));
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass,temperature,heat_flux_x,heat_flux_y,"
              "heat_flux_z");
    EXPECT_NE(csv.find(",0,0,301.5,1,2,3\n"), std::string::npos) << csv;
}
