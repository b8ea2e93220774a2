#pragma once
/// VTK XML output for ParaView (output.vtk_every): per output step one .vtu piece per rank
/// and a .pvtu naming them, for the particles and for the block-forest outlines, and one
/// .pvd time series of each per run:
///
///     <dir>/particles.pvd, <dir>/blocks.pvd           open these in ParaView
///     <dir>/vtk/particles_<step>.pvtu, <dir>/vtk/particles_<step>_r<rank>.vtu
///     <dir>/vtk/blocks_<step>.pvtu,    <dir>/vtk/blocks_<step>_r<rank>.vtu
///     <dir>/grid.pvd                   with cell fields (write() given grid gravity's or others)
///     <dir>/walls.pvd, <dir>/vtk/walls_<step>.vtp      with walls (writeWalls, rank 0)
///     <dir>/vtk/grid_<step>.vtm,       <dir>/vtk/grid_<step>_b<curve index>.vti
///
/// Particles are points (one vertex cell each) with point data uid, radius, mass, velocity,
/// angular_velocity, force, owner_rank, and with shadows on also `shadow` (1 for a shadow
/// copy). Blocks are hexahedra with cell data block_id, owner_rank, level, grains (masters).
/// Grid fields are one image data piece per block (interior cells, origin at the block's
/// lower corner, spacing the cell size) with the fields as cell data (grid gravity's: density,
/// potential and acceleration), and a multi-block .vtm per step naming every block's piece in
/// curve order. Walls are polygons (io/vtk/WallPieces.hpp: infinite ones cut to the domain box)
/// with point data velocity (of the wall's material) and cell data wall (index) and type.
/// No VTK header is visible here: VTK is linked PRIVATE to regolith::io.
#include "core/math/AABB.hpp"
#include "core/mpi/Comm.hpp"
#include "gravity/field/GridFieldsView.hpp"
#include "particles/storage/WallList.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace regolith::io {

struct VtkOptions {
    std::string dir = "out"; ///< output directory (created if missing)
    bool shadows = false;    ///< also write shadow copies (flagged by the `shadow` array)
    bool blocks = true;      ///< also write the block outlines at every output step
    /// A restarted run continues the series of the run it restarts: the entries of existing
    /// .pvd files in `dir` with a time below this are kept (the default keeps none); of the
    /// grid series also the entry at this time, replaced if the grid is written again then
    /// (a restart has no grid to write before its first field update).
    double keepEntriesBefore = -std::numeric_limits<double>::infinity();
    /// Whether this run writes grid fields. A fresh run (keepEntriesBefore at its default)
    /// that does not removes an earlier run's grid.pvd from `dir`, with a warning: it would
    /// otherwise sit beside this run's series as if it belonged to it (its pieces stay). A
    /// grid.pvd that is not a grid series this program writes is left alone, with a warning.
    bool writesGrid = false;
    /// Whether this run writes walls (writeWalls): its walls.pvd is checked like the others.
    bool writesWalls = false;
};

class VtkOutput {
public:
    /// Rank 0 creates <dir>/vtk and reads the entries to keep of existing series (see
    /// VtkOptions::keepEntriesBefore); throws core::InputError on every rank if the directory
    /// cannot be made, or if a .pvd this run writes exists and is not a series of its kind
    /// this program writes (a VTK collection of "vtk/<kind>_<step>..." files): a user's file is
    /// never replaced. COLLECTIVE over `comm`, which must outlive this object.
    VtkOutput(core::Comm const& comm, VtkOptions options);

    /// Writes the state of step `step` at simulated time `time`: every rank its pieces, rank
    /// 0 the .pvtu indices and both .pvd series (rewritten whole each time). Every file goes
    /// to a fresh temporary and is renamed into place (core::replaceFile), so they stay valid
    /// if the run stops and a link under a file's name is replaced, not written through. Throws
    /// core::InputError on every rank if a file cannot be written. With `grid` (grid gravity's
    /// fields, given on every rank alike) also the grid fields of every block and the grid.pvd
    /// series. COLLECTIVE over the communicator.
    void write(std::int64_t step, double time, particles::LocalParticles const& local,
               std::optional<gravity::GridFieldsView> const& grid = std::nullopt);

    /// Writes `walls` as they stand at step `step`, time `time`, cut to `domain`: rank 0 the
    /// piece and the walls.pvd series. Throws core::InputError on every rank if a file cannot
    /// be written. COLLECTIVE over the communicator.
    void writeWalls(std::int64_t step, double time, particles::WallList const& walls,
                    core::AABB const& domain);

    /// The .pvd files this object writes.
    [[nodiscard]] std::string particleSeriesPath() const;
    [[nodiscard]] std::string blockSeriesPath() const;
    [[nodiscard]] std::string gridSeriesPath() const;
    [[nodiscard]] std::string wallSeriesPath() const;

private:
    core::Comm const* m_comm;
    VtkOptions m_options;
    std::vector<std::pair<double, std::string>> m_particleSteps; ///< (time, .pvtu) so far
    std::vector<std::pair<double, std::string>> m_blockSteps;
    std::vector<std::pair<double, std::string>> m_gridSteps;
    std::vector<std::pair<double, std::string>> m_wallSteps;
    /// Every block's curve index in curve order (gathered at the first grid output).
    std::vector<std::uint64_t> m_gridBlocks;
    bool m_gridBlocksKnown = false;
};

} // namespace regolith::io
