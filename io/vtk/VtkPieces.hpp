#pragma once
/// Internal to io/: one rank's piece of a parallel VTK XML data set (.vtu), written with
/// VTK's XML writer (through the VTK module), and the names and types of its arrays, which
/// the .pvtu index written by rank 0 must repeat exactly.
#include "io/vtk/VtkModule.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <string>
#include <vector>

namespace regolith::io::detail {

using vtkxml::ArraySpec;

/// Point data of a particle piece: the entries of particles::kGrainQuantities written to VTK
/// (uid, velocity, angular_velocity, force, radius, mass), owner_rank, with `shadows` also
/// shadow (1 for a shadow copy, 0 for a master), then the declared grain fields.
[[nodiscard]] std::vector<ArraySpec> particleArrays(bool shadows);
/// Cell data of a block piece: block_id, owner_rank, level, grains (masters in the block).
[[nodiscard]] std::vector<ArraySpec> blockArrays();

/// Writes this rank's masters (and shadows, flagged, with `shadows`) as points with one
/// vertex cell each, in raw appended binary. Throws core::Error naming `path` if VTK fails.
/// Not collective.
void writeParticlePiece(std::string const& path, particles::LocalParticles const& local,
                        bool shadows);

/// Writes this rank's blocks as hexahedra with blockArrays() as cell data. Throws
/// core::Error naming `path` if VTK fails. Not collective.
void writeBlockPiece(std::string const& path, particles::LocalParticles const& local);

/// The text of a .pvtu naming `pieces` (paths relative to the .pvtu) with `pointArrays` as
/// point data and `cellArrays` as cell data. Not collective.
[[nodiscard]] std::string pvtuText(std::vector<ArraySpec> const& pointArrays,
                                   std::vector<ArraySpec> const& cellArrays,
                                   std::vector<std::string> const& pieces);

} // namespace regolith::io::detail
