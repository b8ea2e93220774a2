#pragma once
/// The interaction list of a group of targets (Barnes 1990, "A modified tree code: don't
/// laugh; it runs", J. Comput. Phys. 87, 161): the cells accepted as multipoles and the
/// grains of the leaves opened, gathered once for the whole group by a walk against the
/// group's bounding box, then evaluated for every target of the group in one SoA batch.
#include "core/math/AABB.hpp"
#include "gravity/tree/Octree.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::gravity::tree {

class InteractionList {
public:
    void clear();

    /// A multipole: monopole + quadrupole of `cell` (monopole only if !quadrupole, stored
    /// with the grains).
    void addCell(TreeNode const& cell, bool quadrupole);
    /// Grains [begin, end) of `tree` (point masses).
    void addGrains(TreeView const& tree, std::int32_t begin, std::int32_t end);

    [[nodiscard]] std::size_t cellCount() const { return m_cx.size(); }
    [[nodiscard]] std::size_t grainCount() const { return m_px.size(); }

    /// Field at targets [0, n) (positions tx, ty, tz) of everything in the list, added to
    /// ax, ay, az, phi. A grain at zero distance from a target (itself) is skipped. The
    /// inner loops run over targets (vectorisable, no reassociation needed). Cell term, with
    /// r = x - com, r² softened by ε²:
    ///   a = -G [M r / r³ - Q r / r⁵ + 5/2 (rᵀQr) r / r⁷],  φ = -G [M / r + ½ rᵀQr / r⁵].
    void evaluate(double const* tx, double const* ty, double const* tz, std::size_t n, double G,
                  double eps2, double* ax, double* ay, double* az, double* phi) const;

private:
    std::vector<double> m_cx, m_cy, m_cz, m_cm;
    std::vector<double> m_qxx, m_qyy, m_qzz, m_qxy, m_qxz, m_qyz;
    std::vector<double> m_px, m_py, m_pz, m_pm;
};

/// Walks `tree` from its root for targets inside the closed box `group`: a cell whose com
/// is farther than rcrit from the box (so from every target) is added as a multipole, as
/// is a closed cell of a locally essential tree; an opened leaf adds its grains; other cells
/// are opened. `stack` is scratch space. Not collective.
void collectInteractions(TreeView const& tree, core::AABB const& group, bool quadrupole,
                         InteractionList& list, std::vector<std::int32_t>& stack);

} // namespace regolith::gravity::tree
