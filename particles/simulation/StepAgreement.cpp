#include "particles/simulation/StepAgreement.hpp"

#include <span>

namespace regolith::particles {

void BeforeSyncAgreement::reduce(core::Comm const& comm) {
    if (comm.size() == 1)
        return;
    // The smallest edge and quiet motion as the largest of their negatives.
    std::array<double, 5> v{moved, share, -edge, static_cast<double>(verdict), -quiet};
    comm.allReduceInPlace(std::span<double>(v), core::ReduceOp::Max);
    moved = v[0];
    share = v[1];
    edge = -v[2];
    verdict = static_cast<SyncVerdict>(static_cast<int>(v[3]));
    quiet = -v[4];
}

void AfterSyncAgreement::reduce(core::Comm const& comm) {
    if (comm.size() == 1)
        return;
    std::array<double, 4> v{listDue ? 1.0 : 0.0, bodyForceVote[0], bodyForceVote[1],
                            syncListHolds ? 0.0 : 1.0};
    comm.allReduceInPlace(std::span<double>(v), core::ReduceOp::Max);
    listDue = v[0] != 0.0;
    bodyForceVote = {v[1], v[2]};
    syncListHolds = v[3] == 0.0;
}

} // namespace regolith::particles
