#pragma once
/// The `conserved` block of the run summary, computed from the masters of all ranks.
#include "apps/common/MasterRecord.hpp"
#include "apps/common/RunSummary.hpp"
#include "core/mpi/Comm.hpp"

#include <span>

namespace regolith::apps {

/// For solid homogeneous spheres (moment of inertia I = 2/5 m r^2):
///  - momentum             sum m v;
///  - angular_momentum     sum (x cross m v + I w), about the origin;
///  - kinetic_energy       sum (1/2 m |v|^2 + 1/2 I |w|^2), of which the rotational part
///                         sum 1/2 I |w|^2 (rotational_kinetic_energy);
///  - potential_energy     sum -m g.x in the uniform external field `gravity` (self-gravity
///                         energy is not included: it belongs to the gravity module);
///  - center_of_mass       sum m x / sum m (zero when there is no mass);
///  - mass                 sum m (beyond the contract of docs/design.md, "Run summary").
/// Positions are taken as stored, i.e. wrapped into the domain on periodic axes (where the
/// angular momentum and centre of mass are frame quantities, not conserved ones). Summed
/// locally in storage order, then over ranks with MPI_Allreduce: equal for any rank count to
/// rounding (relative ~1e-15 per term), not bitwise. Same result on every rank.
/// COLLECTIVE over `comm`.
[[nodiscard]] RunSummary::Conserved conservedQuantities(core::Comm const& comm,
                                                        std::span<MasterRecord const> local,
                                                        core::Vec3 const& gravity);
/// The same from a source of masters (same order, same sums bit for bit). COLLECTIVE.
[[nodiscard]] RunSummary::Conserved conservedQuantitiesFrom(core::Comm const& comm,
                                                            MasterSource const& local,
                                                            core::Vec3 const& gravity);

} // namespace regolith::apps
