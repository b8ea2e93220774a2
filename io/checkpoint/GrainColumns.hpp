#pragma once
/// Internal to io/: grains as columns (one array per stored field), the form in which they go
/// to and come from the checkpoint's datasets (CheckpointInfo.hpp lists the layout).
#include "io/checkpoint/GrainState.hpp"
#include "io/checkpoint/Hdf5Module.hpp"
#include "particles/storage/GrainQuantities.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace regolith::io::detail {

struct GrainColumns {
    std::size_t grains = 0;
    /// One column per entry of particles::kGrainQuantities (those not written to checkpoints
    /// stay empty), components row by row.
    particles::GrainElementColumns quantities;
    std::vector<std::uint64_t> historyOffset; ///< global index of the grain's first entry
    std::vector<std::uint32_t> historyCount;
    std::vector<std::uint64_t> partner; ///< history entries, grain after grain
    std::vector<double> spring;
    std::vector<std::uint32_t> stamp;
    /// Per declared grain field (particles::grainFields order), its components row by row.
    std::vector<std::vector<double>> fields;

    /// Resizes every grain column to `grains` rows and every history column to `entries`.
    void resize(std::size_t grains, std::size_t entries);
};

/// Every column of `c`, in the file's order. The views point into `c`.
[[nodiscard]] std::vector<ColumnView> columnViews(GrainColumns& c);

/// `grains` as columns; the history offsets start at `historyBase` (the number of entries
/// stored before this slice).
[[nodiscard]] GrainColumns toColumns(std::span<GrainState const> grains, std::uint64_t historyBase);

/// The grains back from columns whose history offsets start at `historyBase`. Throws
/// core::InputError (prefixed with `context`) if an offset or count points outside the
/// history columns.
[[nodiscard]] std::vector<GrainState> fromColumns(GrainColumns const& c, std::uint64_t historyBase,
                                                  std::string const& context);

} // namespace regolith::io::detail
