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
#include <vector>

namespace regolith::coupling {

/// |a - a_direct| / |a_direct| of the grains whose uid a hash selects, about `sample` of them
/// over all ranks (the same grains on any layout), where `field` is the acceleration a of the
/// local `grains` (uids `uid`) to be judged and a_direct the Plummer-softened direct sum over
/// all grains of all ranks (G, softening). The same list, in the same order (by rank, then as
/// stored), on every rank; grains with a_direct = 0 are left out. Cost: sample x grains pair
/// terms, shared by the ranks. Empty without grains. COLLECTIVE over `comm`.
[[nodiscard]] std::vector<double> sampledForceErrors(core::Comm const& comm,
                                                     gravity::PointMasses const& grains,
                                                     std::span<std::uint64_t const> uid,
                                                     gravity::AccelView const& field, double G,
                                                     double softening, std::size_t sample);

/// The median, 99th percentile and maximum of sampledForceErrors (all zero without grains).
/// COLLECTIVE over `comm`.
[[nodiscard]] gravity::ErrorStats sampledForceError(core::Comm const& comm,
                                                    gravity::PointMasses const& grains,
                                                    std::span<std::uint64_t const> uid,
                                                    gravity::AccelView const& field, double G,
                                                    double softening, std::size_t sample);

} // namespace regolith::coupling
