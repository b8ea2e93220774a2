#pragma once
/// Particle snapshots for analysis (output.dump_every, output.dump_format): every N steps, and
/// at the start of a new run, the state of every grain in output.dir/dumps/, as
/// particles_<step>.csv (the --dump format: rank 0 gathers the grains, sorted by uid) or
/// particles_<step>.h5 (the checkpoint format, written by every rank through MPI-IO; its
/// datasets carry `units` and `description` attributes, and it restarts like a checkpoint).
#include "apps/regolith/Checkpointing.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <string>

namespace regolith::apps {

/// output.dir/dumps/particles_<step, 8 digits>.<csv | h5>. Not collective.
[[nodiscard]] std::string snapshotPath(OutputSection const& output, std::int64_t step);

class ParticleSnapshots {
public:
    /// Creates output.dir/dumps if snapshots are due at all; throws core::InputError on every
    /// rank if it cannot. `local` and `checkpoints` (which writes the HDF5 files) must outlive
    /// this object. COLLECTIVE over `comm`.
    ParticleSnapshots(core::Comm const& comm, OutputSection const& output,
                      particles::LocalParticles const& local, CheckpointSchedule& checkpoints);
    /// Whether a snapshot is due after `stepsDone` steps. Not collective.
    [[nodiscard]] bool due(std::int64_t stepsDone) const {
        return m_output.dumpEvery > 0 && stepsDone % m_output.dumpEvery == 0;
    }
    /// Writes the snapshot of step `stepsDone`. COLLECTIVE.
    void write(std::int64_t stepsDone);

private:
    core::Comm const* m_comm;
    OutputSection m_output;
    particles::LocalParticles const* m_local;
    CheckpointSchedule* m_checkpoints;
};

} // namespace regolith::apps
