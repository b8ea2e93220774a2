#pragma once
/// Internal to io/: cell fields (grid gravity's, a program's own) as VTK image data, one .vti file
/// per block (interior cells only, ghost layers excluded), and the .vtm multi-block index that
/// gathers every block of an output step so that ParaView shows them together.
#include "gravity/field/GridFieldsView.hpp"
#include "io/vtk/VtkPieces.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace regolith::io::detail {

/// Cell data of a grid piece: one Float64 array per field of `fields`, named and sized as it.
[[nodiscard]] std::vector<ArraySpec> gridArrays(gravity::GridFieldsView const& fields);

/// Writes local block b of `fields` as image data: origin at the block's lower corner,
/// spacing the cell size, one VTK cell per grid cell (x fastest) with gridArrays() as cell
/// data. Throws core::Error naming `path` if VTK fails. Not collective.
void writeGridPiece(std::string const& path, gravity::GridFieldsView const& fields, std::size_t b);

/// One block in a multi-block index: its name and its file (relative to the .vtm).
struct BlockPiece {
    std::string name;
    std::string file;
};

/// The text of a .vtm (vtkMultiBlockDataSet, XML format 1.0) naming `pieces` in order.
/// Not collective.
[[nodiscard]] std::string vtmText(std::vector<BlockPiece> const& pieces);

} // namespace regolith::io::detail
