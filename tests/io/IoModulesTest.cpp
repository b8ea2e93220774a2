// VTK and HDF5 are loaded only when a run first writes VTK output or a checkpoint
// (io/vtk/VtkModule.hpp, io/checkpoint/Hdf5Module.hpp): a process that writes neither maps
// none of their libraries. This executable links neither itself.
#include "domain/BlockForest.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/vtk/VtkOutput.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "tests/harness/MappedLibraries.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

using namespace regolith;
using regolith::test::isMapped;

TEST(IoModules, VtkLoadedOnFirstOutputOnly) {
    core::Comm const world;
    domain::ForestSpec spec;
    spec.domain = core::AABB{core::Vec3::Zero(), core::Vec3::Constant(4.0)};
    spec.rootBlocks = {1, 1, 1};
    domain::BlockForest const forest(world, spec);
    particles::LocalParticles local(forest);
    particles::ParticleInit grain;
    grain.uid = 7;
    grain.position = core::Vec3::Constant(2.0);
    grain.radius = 0.5;
    grain.mass = 1.0;
    ASSERT_TRUE(local.addMaster(grain));

    std::filesystem::remove_all("vtk_module_test");
    io::VtkOutput out(world, io::VtkOptions{"vtk_module_test", false, true});
    EXPECT_FALSE(isMapped("libvtk")) << "VTK was mapped before the first output";
    EXPECT_FALSE(isMapped("libregolith_vtk"));
    out.write(0, 0.0, local);
    EXPECT_TRUE(isMapped("libregolith_vtk"));
    EXPECT_TRUE(isMapped("libvtkIOXML"));
    EXPECT_TRUE(
        std::filesystem::is_regular_file("vtk_module_test/vtk/particles_00000000_r0000.vtu"));
    EXPECT_TRUE(std::filesystem::is_regular_file("vtk_module_test/particles.pvd"));
}

TEST(IoModules, Hdf5LoadedOnFirstCheckpointOnly) {
    core::Comm const world;
    io::GrainState grain;
    grain.uid = 3;
    grain.position = core::Vec3(1.0, 2.0, 3.0);
    grain.radius = 0.5;
    grain.mass = 2.0;
    std::vector<io::GrainState> const grains{grain};
    io::CheckpointInfo info;
    info.step = 12;
    EXPECT_FALSE(isMapped("libhdf5")) << "HDF5 was mapped before the first checkpoint";
    EXPECT_FALSE(isMapped("libregolith_hdf5"));
    (void)io::writeCheckpoint(world, "hdf5_module_test.h5", info, grains);
    EXPECT_TRUE(isMapped("libregolith_hdf5"));
    EXPECT_TRUE(isMapped("libhdf5"));
    io::CheckpointSlice const back = io::readCheckpoint(world, "hdf5_module_test.h5");
    EXPECT_EQ(back.info.step, 12);
    ASSERT_EQ(back.grains.size(), 1U);
    EXPECT_EQ(back.grains[0].position, grain.position);
}
