#include "apps/regolith/ParticleSnapshots.hpp"

#include "apps/common/OutputFile.hpp"
#include "apps/common/StateDump.hpp"
#include "apps/regolith/LoopSummary.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace regolith::apps {

std::string snapshotPath(OutputSection const& output, std::int64_t step) {
    std::string const name = fmt::format("particles_{:08d}.{}", step,
                                         output.dumpFormat == DumpFormat::Hdf5 ? "h5" : "csv");
    return (std::filesystem::path(output.dir) / "dumps" / name).string();
}

ParticleSnapshots::ParticleSnapshots(core::Comm const& comm, OutputSection const& output,
                                     particles::LocalParticles const& local,
                                     CheckpointSchedule& checkpoints)
    : m_comm(&comm)
    , m_output(output)
    , m_local(&local)
    , m_checkpoints(&checkpoints) {
    if (m_output.dumpEvery > 0) // creates the folder, or says why not on every rank
        checkWritable(comm, snapshotPath(m_output, 0), "output.dump_every");
}

void ParticleSnapshots::write(std::int64_t stepsDone) {
    std::string const path = snapshotPath(m_output, stepsDone);
    if (m_output.dumpFormat == DumpFormat::Hdf5)
        (void)m_checkpoints->writeTo(path, stepsDone);
    else
        writeFileOnRoot(*m_comm, path, gatherDumpCsv(*m_comm, masterRecords(*m_local)));
}

} // namespace regolith::apps
