#pragma once
/// Particle <-> mesh transfer: deposition of grain mass onto the cells as a density, and
/// interpolation of cell fields back to grains, with the same kernel (CIC or TSC) and the
/// same ball samples (see AssignmentKernels.hpp). Grains are given as SoA spans, so the
/// module needs no particle type.
///
/// Where the mass goes: every cell a grain's kernel touches, on whichever rank owns it. Cells
/// of local blocks are written directly; contributions to cells of other ranks are summed in
/// a per-rank sparse map and sent with core::SparseExchange (NBX), so a grain may be larger
/// than a block and deposit into blocks that are not neighbours of its own. Interpolation
/// mirrors this with a request / reply round for remote cells. No ghost layer is used.
#include "core/math/Vec3.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "gravity/field/CellField.hpp"
#include "gravity/transfer/AssignmentKernels.hpp"

#include <memory>
#include <span>
#include <vector>

namespace regolith::gravity {

/// The grains this rank contributes (each grain on exactly one rank). Units: position and
/// radius [length], mass [mass]. radius and mass may be empty where not needed. `mass` is the
/// weight deposited: a grain's mass for gravity, or any quantity per grain (1 for a number
/// density, a momentum component, a charge), of either sign.
struct Grains {
    std::span<core::Vec3 const> position;
    std::span<double const> radius;
    std::span<double const> mass;
};

class MeshTransfer {
public:
    /// Pre: `layout` outlives this object. COLLECTIVE over `comm` (duplicates it).
    MeshTransfer(core::Comm const& comm, CellLayout const& layout, Assignment scheme);
    ~MeshTransfer();
    MeshTransfer(MeshTransfer const&) = delete;
    MeshTransfer& operator=(MeshTransfer const&) = delete;

    [[nodiscard]] Assignment scheme() const { return m_scheme; }

    /// Adds the mass density [mass / length^3] of `grains` to the interior cells of component
    /// 0 of `density` (call density.fill(0) first for a fresh deposit). Mass is conserved to
    /// round-off. Throws core::InputError on every rank if any rank's grain is not finite, has
    /// a negative radius, or puts mass outside the domain on a non-periodic axis (the
    /// message of the rank that found it names position, radius and domain; the field is
    /// then partly updated). COLLECTIVE over the communicator.
    void deposit(Grains const& grains, CellField& density);

    /// For each grain i and component c of `field`: out[i * components + c] = the kernel- and
    /// sample-weighted average of the interior cell values around grain i (mass not used).
    /// Pre: out.size() == grains.position.size() * field.components(). Same errors as
    /// deposit() for grains outside the domain. COLLECTIVE over the communicator.
    void interpolate(Grains const& grains, CellField const& field, std::span<double> out);

private:
    /// Calls visit(owner, weight) for every cell touched by grain i, weights summing to 1.
    /// Returns false (and stops) if a cell lies outside the domain.
    template <class Visit>
    bool forEachCell(Grains const& grains, std::size_t i, Visit&& visit);
    /// forEachCell's fast path for one sample's stencil: visits its cells and returns true if
    /// they all lie in one block without wrapping, else visits nothing and returns false.
    template <class Visit>
    bool visitInOneBlock(std::array<Stencil1D, 3> const& s, double sampleWeight,
                         Visit& visit) const;
    /// Agrees on `error` over all ranks; throws core::InputError everywhere if any is set.
    void agree(std::string const& error) const;

    core::Comm m_comm;
    CellLayout const* m_layout;
    Assignment m_scheme;
    std::unique_ptr<core::SparseExchange> m_exchange;
    std::vector<core::Vec3> m_samples;
};

} // namespace regolith::gravity
