// VTK is loaded only when a run first writes VTK output (io/vtk/VtkModule.hpp): a process
// that writes none maps none of VTK's libraries. This executable links no VTK itself.
#include "domain/BlockForest.hpp"
#include "io/vtk/VtkOutput.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "tests/harness/MappedLibraries.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace regolith;
using regolith::test::isMapped;

TEST(VtkModule, LoadedOnFirstOutputOnly) {
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
