#pragma once
/// Every master of the run on every rank, in uid order: the input of the pile's measures
/// (PileMeasures, Remnants), which then sum in the same order on any number of ranks and any
/// block layout, so that what they feed back into the run (the spin-up torque's centre and
/// rate) keeps a reproducible run's bits.
#include "apps/common/MasterRecord.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <vector>

namespace regolith::apps {

/// All ranks' masters, sorted by uid, on every rank (96 bytes a grain: 2 MB for 20,000).
/// COLLECTIVE.
[[nodiscard]] std::vector<MasterRecord> gatherMastersByUid(core::Comm const& comm,
                                                           particles::LocalParticles const& local);

} // namespace regolith::apps
