#pragma once
/// The gravity-only halo of P3M: for this rank's grains, every grain of another rank (and
/// every periodic image of any grain) closer than the short-range cut-off to one of this
/// rank's blocks, with its position in this rank's frame. The particle synchronisation's
/// shadows do not serve: they exist only where a grain overlaps a block (contact range),
/// while the P3M correction reaches a few grid cells.
///
/// Scheme: built once per forest, every local block lists the images of the root blocks
/// within the cut-off (owner rank from the cell layout's block table, periodic shift), itself
/// excepted. Per gather, a grain at least one cut-off inside its block's faces is skipped at
/// once; any other is sent once to every (rank, image) whose block image lies within the
/// cut-off of it (core::SparseExchange, NBX: no collective beyond the exchange's own
/// reduction; images on this rank are copied without MPI). Cost per gather: O(local grains)
/// tests plus the traffic of the grains within one cut-off of a block face, 32 bytes each
/// (position and mass) per destination.
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "domain/BlockForest.hpp"
#include "gravity/field/CellLayout.hpp"

#include <span>
#include <vector>

namespace regolith::coupling {

class ShortRangeHalo {
public:
    /// `layout` answers the owner of any root block (an unrefined forest); both must outlive
    /// this object. `cutoff` > 0 [length]. COLLECTIVE over `comm` (the exchange duplicates
    /// it).
    ShortRangeHalo(core::Comm const& comm, domain::BlockForest const& forest,
                   gravity::CellLayout const& layout, double cutoff);

    /// Exchanges the halo of the local grains `position` (wrapped into the domain on periodic
    /// axes, each inside a local block) and `mass`. Replaces the previous halo. COLLECTIVE.
    void gather(std::span<core::Vec3 const> position, std::span<double const> mass);

    /// The halo of the last gather: positions in this rank's frame [length], masses.
    [[nodiscard]] std::span<core::Vec3 const> position() const { return m_position; }
    [[nodiscard]] std::span<double const> mass() const { return m_mass; }
    /// Grains sent to other ranks in the last gather (all destinations counted).
    [[nodiscard]] std::size_t sentLastGather() const { return m_sent; }

private:
    /// The image of a root block near a local block.
    struct Image {
        int rank = -1;
        core::Vec3 shift = core::Vec3::Zero(); ///< image box = owner's box + shift
        core::AABB box;                        ///< in this rank's frame
    };
    /// Destinations of grain x of local block b (or of every block if b < 0), deduplicated.
    void destinations(core::Vec3 const& x, int b);

    domain::BlockForest const* m_forest;
    double m_cutoff;
    int m_rank;
    std::vector<std::vector<Image>> m_images; ///< per local block
    core::SparseExchange m_exchange;
    std::vector<Image const*> m_found; ///< scratch for destinations()
    std::vector<core::Vec3> m_position;
    std::vector<double> m_mass;
    std::size_t m_sent = 0;
};

} // namespace regolith::coupling
