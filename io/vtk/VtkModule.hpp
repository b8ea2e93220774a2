#pragma once
/// Every VTK call of the simulation's output sits behind this interface, implemented by a
/// shared module (libregolith_vtk.so, VtkModule.cpp) that is loaded with dlopen the first time
/// a run writes VTK output (core/module/SharedModule.hpp). A run without VTK output then maps
/// none of VTK's libraries: 9.5 MB of resident pages in every process (docs/notes/memory.md). No
/// VTK header here; the callers hand over plain arrays, which the module wraps without copying.
#include "io/vtk/VtkSeries.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace regolith::io::vtkxml {

/// One data array as a .pvtu declares it: name, VTK XML type, components.
struct ArraySpec {
    std::string name;
    std::string type; ///< "Float64", "Int32", "Int64", "UInt64", "UInt32", "UInt8"
    int components = 1;
};

/// An array's values: `components` per tuple, as many tuples as the data set has points or
/// cells, of the C++ type that `spec.type` names. Read only; must outlive the call.
struct Column {
    ArraySpec spec;
    void const* values;
};

class Module {
public:
    virtual ~Module() = default;
    /// Writes `count` points (`xyz`: 3 per point), one vertex cell each, with `pointData`, as
    /// a .vtu in raw appended binary with 64-bit headers. False if VTK fails.
    [[nodiscard]] virtual bool writeVertices(std::string const& path, std::size_t count,
                                             double const* xyz,
                                             std::vector<Column> const& pointData) = 0;
    /// Writes `count` axis-aligned boxes (`bounds`: min x, y, z then max x, y, z per box) as
    /// hexahedra with `cellData`, as writeVertices. False if VTK fails.
    [[nodiscard]] virtual bool writeBoxes(std::string const& path, std::size_t count,
                                          double const* bounds,
                                          std::vector<Column> const& cellData) = 0;
    /// Writes `count` points (`xyz`: 3 per point) and polygons (polygon k: the points
    /// connectivity[offsets[k] .. offsets[k+1]), offsets starting with 0) with `pointData` and
    /// `cellData`, as VTK XML polydata (.vtp), as writeVertices. False if VTK fails.
    [[nodiscard]] virtual bool writePolygons(std::string const& path, std::size_t count,
                                             double const* xyz,
                                             std::vector<std::int64_t> const& offsets,
                                             std::vector<std::int64_t> const& connectivity,
                                             std::vector<Column> const& pointData,
                                             std::vector<Column> const& cellData) = 0;
    /// Writes image data of `cells` cells per axis (the first axis fastest in `cellData`) with
    /// its lower corner at `origin` and cell size `spacing`, as writeVertices. False if VTK
    /// fails.
    [[nodiscard]] virtual bool writeImage(std::string const& path, std::array<int, 3> cells,
                                          std::array<double, 3> origin,
                                          std::array<double, 3> spacing,
                                          std::vector<Column> const& cellData) = 0;
    /// The data sets of a .pvd collection, in file order, into `out`. Returns "" or what is
    /// wrong with the file (unreadable, not a collection, a data set without file or time).
    [[nodiscard]] virtual std::string readCollection(std::string const& path,
                                                     std::vector<SeriesEntry>& out) = 0;
};

/// The module, loaded on the first call (REGOLITH_VTK_MODULE, else the build's copy, else
/// ../lib/ beside the executable), with VTK's own message printing off: Regolith reports
/// failures itself, once. Throws core::Error naming the paths tried.
Module& module();

} // namespace regolith::io::vtkxml

/// The module's one exported symbol.
extern "C" regolith::io::vtkxml::Module* regolith_vtk_module();
