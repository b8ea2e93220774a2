// Tutorial 04: a grid field of one's own, deposited from the grains and written for ParaView.
//
// Grains rain onto a floor in a box with periodic sides. Every 200 steps an observer deposits
// their number density and their mean velocity onto the cells of the blocks (cloud-in-cell,
// across block and rank boundaries, gravity::MeshTransfer) and writes grains, blocks and both
// fields as VTK (io::VtkOutput): open tutorial04/particles.pvd and tutorial04/grid.pvd in
// ParaView. Run: mpiexec -n 2 ./04-grid-field [steps].
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/random/CounterRng.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "gravity/field/CellField.hpp"
#include "gravity/field/CellLayout.hpp"
#include "gravity/transfer/MeshTransfer.hpp"
#include "io/vtk/VtkOutput.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

using namespace regolith;
using core::Vec3;

namespace {

constexpr double kRadius = 0.4;
constexpr std::array<int, 3> kCellsPerBlock{8, 8, 8}; // blocks of 8^3: cells of edge 1

/// The local grains as the mesh transfer takes them (SoA), with one weight per grain: 1 for
/// the number density, m v_a for the momentum density along axis a.
struct GrainColumns {
    std::vector<Vec3> position;
    std::vector<double> radius, mass;
    std::array<std::vector<double>, 3> momentum;

    explicit GrainColumns(coupling::Simulation& sim) {
        sim.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
            position.push_back(g.position(i));
            radius.push_back(g.radius(i));
            mass.push_back(g.mass(i));
            for (int a = 0; a < 3; ++a)
                momentum[a].push_back(g.mass(i) * g.velocity(i)[a]);
        });
    }
    [[nodiscard]] gravity::Grains weighted(std::vector<double> const& weight) const {
        return {position, radius, weight};
    }
};

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    core::Comm const world;
    int const steps = argc > 1 ? std::atoi(argv[1]) : 4000;

    coupling::SimulationSetup setup;
    // The floor at z = 0 lies a cell above the domain's bottom: a grain on it deposits into
    // the cells below it too (the cloud-in-cell kernel is a cell wide).
    setup.domain.domain = core::AABB{Vec3(0.0, 0.0, -1.0), Vec3(16.0, 16.0, 31.0)};
    setup.domain.rootBlocks = {2, 2, 4};
    setup.domain.periodic = {true, true, false};
    particles::LinearContactParams contact;
    contact.stiffness = 2000.0;
    contact.tangentialStiffness = 2.0 / 7.0 * contact.stiffness;
    contact.restitution = 0.5;
    contact.friction = 0.5;
    setup.contact = particles::SpringDashpot(
        particles::MaterialTable<particles::LinearContactParams>(1, contact));
    setup.dem.dt = 1e-3;
    setup.dem.gravity = Vec3(0.0, 0.0, -1.0);
    setup.walls.add(Vec3::Zero(), Vec3::UnitZ()); // the floor
    coupling::Simulation sim(world, setup);

    // 12 x 12 x 16 grains in the upper part of the box, slightly jittered, at rest.
    double const mass = 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
    particles::Uid uid = 0;
    for (int k = 0; k < 16; ++k)
        for (int j = 0; j < 12; ++j)
            for (int i = 0; i < 12; ++i, ++uid) {
                core::random::CounterRng rng(7, uid);
                particles::ParticleInit p;
                p.uid = uid;
                p.position = Vec3(1.0 + 1.2 * i + rng.uniform(-0.1, 0.1),
                                  1.0 + 1.2 * j + rng.uniform(-0.1, 0.1), 8.0 + 1.2 * k);
                p.radius = kRadius;
                p.mass = mass;
                sim.addGrain(p);
            }
    sim.start();

    // The grid: cells on the simulation's blocks (the same forest, the same ranks), a
    // cloud-in-cell transfer, and the fields. One ghost layer (the layout's minimum).
    gravity::CellLayout const layout(world, sim.forest(), kCellsPerBlock, 1);
    gravity::MeshTransfer transfer(world, layout, gravity::Assignment::Cic);
    gravity::CellField number(layout);      // grains per volume
    gravity::CellField component(layout);   // one momentum component per volume (scratch)
    gravity::CellField velocity(layout, 3); // mass-weighted mean velocity of the grains
    gravity::CellField massDensity(layout);
    io::VtkOutput vtk(world, io::VtkOptions{.dir = "tutorial04", .writesGrid = true});

    double counted = 0.0; // grains on the grid at the last output, for the check below
    auto const output = [&](coupling::Simulation& s) {
        GrainColumns const grains(s);
        std::vector<double> const ones(grains.position.size(), 1.0);
        number.fill(0.0);
        transfer.deposit(grains.weighted(ones), number);
        massDensity.fill(0.0);
        transfer.deposit(grains.weighted(grains.mass), massDensity);
        for (int a = 0; a < 3; ++a) {
            component.fill(0.0);
            transfer.deposit(grains.weighted(grains.momentum[a]), component);
            for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
                for (int z = 0; z < kCellsPerBlock[2]; ++z)
                    for (int y = 0; y < kCellsPerBlock[1]; ++y)
                        for (int x = 0; x < kCellsPerBlock[0]; ++x) {
                            double const rho = massDensity.at(b, x, y, z);
                            velocity.at(b, x, y, z, a) =
                                rho > 0.0 ? component.at(b, x, y, z) / rho : 0.0;
                        }
        }
        counted =
            world.allReduce(number.localInteriorSum(), core::ReduceOp::Sum) * layout.cellVolume();
        vtk.write(s.stepsDone(), s.time(), s.grains(),
                  gravity::GridFieldsView{&layout,
                                          {{"number_density", &number}, {"velocity", &velocity}}});
        if (world.rank() == 0)
            std::printf("step %5lld: %.1f grains on the grid\n",
                        static_cast<long long>(s.stepsDone()), counted);
    };
    output(sim);
    sim.addObserver(200, output);
    sim.run(steps);

    // The deposit conserves the grains: the number density integrates to the grain count.
    bool const conserved = std::abs(counted - static_cast<double>(uid)) < 1e-9 * uid;
    return conserved ? 0 : 1;
}
