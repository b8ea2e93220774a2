#pragma once
/// The force error of a run's self-gravity measured on the run's own grains: the field of a
/// sample of grains against the direct sum over all of them. The grid methods' accuracy check
/// before the run is an estimate from another body (apps/regolith/GridAccuracy.hpp); P3M
/// measured 2.4-5 times worse than that estimate on other bodies (a uniform cloud, two
/// rubble piles), so a run that asks for an accuracy checks the real one after set-up.
#include "core/mpi/Comm.hpp"
#include "gravity/common/ForceError.hpp"
#include "gravity/common/PointMasses.hpp"

#include <cstdint>
#include <span>

namespace regolith::coupling {

/// The median of |a - a_direct| / |a_direct| over the grains whose uid a hash selects, about
/// `sample` of them over all ranks (the same grains on any layout), where `field` is the
/// method's acceleration of the local `grains` (uids `uid`) and a_direct the Plummer-softened
/// direct sum over all grains of all ranks (G, softening). Cost: sample x grains pair terms,
/// shared by the ranks. 0 without grains. COLLECTIVE over `comm`.
[[nodiscard]] double sampledMedianError(core::Comm const& comm, gravity::PointMasses const& grains,
                                        std::span<std::uint64_t const> uid,
                                        gravity::AccelView const& field, double G, double softening,
                                        std::size_t sample);

} // namespace regolith::coupling
