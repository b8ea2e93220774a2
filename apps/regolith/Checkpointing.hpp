#pragma once
/// Checkpoints of a `regolith` run (output.checkpoint_every, output.checkpoint_keep) and the
/// restart from one (--restart FILE), on top of io/checkpoint.
#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/app/RunApp.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace regolith::apps {

/// The scene as text, stored in every checkpoint for provenance: the scene file (or the
/// app's embedded scene, ctx.defaultScene), then each command-line override as a comment
/// line. Rank 0 reads, every rank gets the same text. COLLECTIVE over ctx.world.
[[nodiscard]] std::string sceneText(core::AppContext const& ctx);

/// Throws core::InputError (the same on every rank) naming `path` and both domains unless the
/// checkpoint was written for the scene's domain box and periodicity. Not collective.
void requireSameDomain(std::string const& path, io::CheckpointInfo const& info,
                       SceneDescription const& scene);

/// `text` (sceneText's) with the values "auto" chose appended as "# auto: key=value" lines:
/// a restart reuses them (reuseAutoChoices), and compares scenes with them applied.
[[nodiscard]] std::string withAutoChoices(std::string text, std::vector<AutoChoice> const& choices);

/// For a restart of a scene with "auto" keys: the values the checkpoint's run chose (the
/// "# auto:" lines of `storedText`, the checkpoint's scene), applied to ctx.scene as overrides
/// for the keys that are "auto" here, and `scene` parsed again; returns them (reason "from the
/// checkpoint"). Re-deriving them from the restored grains could change them, and with them
/// the trajectory. Throws core::InputError on every rank naming the keys if the checkpoint
/// lacks one (written before 2026-11-27, or by a run that set them). COLLECTIVE.
[[nodiscard]] std::vector<AutoChoice>
reuseAutoChoices(core::AppContext& ctx, SceneDescription& scene, std::string const& storedText);

/// Checks that the checkpoint `slice` (read from `path`, its domain already checked with
/// requireSameDomain) belongs to `scene`: a step not beyond time.steps. A different time step, or a
/// scene
/// (`sceneText`, as sceneText() and withAutoChoices give it) that differs from the
/// checkpoint's in other sections than [output] and [time], is allowed with a warning naming
/// them. Throws the same core::InputError on every rank naming the file and what differs.
/// COLLECTIVE over `comm`.
void checkRestart(core::Comm const& comm, std::string const& path, io::CheckpointSlice const& slice,
                  SceneDescription const& scene, std::string const& sceneText);

/// Where the time-step loop starts: step 0 at time 0, or a checkpoint's step and time (and
/// the checkpoint, for the self-gravity state restored once that exists).
struct RunStart {
    std::int64_t step = 0;
    double time = 0.0;
    std::optional<io::CheckpointSlice> checkpoint;
};

/// The masters of a restarted run into `local`, from the checkpoint `slice` of --restart FILE
/// (any rank count; read from `started`, an MPI_Wtime, for the log line), checked with
/// checkRestart and against the state checksum the writer stored. Returns the checkpoint's
/// step and time. COLLECTIVE.
[[nodiscard]] RunStart restoreState(core::AppContext const& ctx, SceneDescription const& scene,
                                    std::string const& text, io::CheckpointSlice slice,
                                    double started, particles::LocalParticles& local);

/// Hands the self-gravity state of a checkpoint (this rank's slice of the per-grain records,
/// and the run-wide state) to `selfGravity`, which brings each record to its grain's rank at
/// the next step. Not collective.
void restoreSelfGravity(io::CheckpointSlice const& slice, coupling::SelfGravityForces& selfGravity);

/// Writes a checkpoint every output.checkpoint_every steps into output.dir, as
/// checkpoint_<step>.h5, keeping the newest output.checkpoint_keep.
class CheckpointSchedule {
public:
    /// Simulated time after a step [time].
    using TimeAt = std::function<double(std::int64_t step)>;
    /// Creates output.dir (rank 0) if checkpoints are due at all; throws core::InputError on
    /// every rank if it cannot. COLLECTIVE over `comm`, which must outlive this object, as
    /// must `local`.
    CheckpointSchedule(core::Comm const& comm, SceneDescription const& scene, std::string text,
                       particles::LocalParticles const& local, TimeAt timeAt);

    /// Warns (rank 0) if output.dir holds checkpoints of the steps this run will write after
    /// `firstStep` up to `lastStep`, an earlier run's: they will be replaced. Throws
    /// core::InputError on every rank, before the first step, if one of those names is not a
    /// file, or not an HDF5 file (a directory there would only fail the rename after the run;
    /// any other file would be lost). COLLECTIVE.
    void checkReplaced(std::int64_t firstStep, std::int64_t lastStep) const;
    /// Whether afterStep(stepsDone) writes a checkpoint. Not collective.
    [[nodiscard]] bool due(std::int64_t stepsDone) const {
        return m_output.checkpointEvery > 0 && stepsDone % m_output.checkpointEvery == 0;
    }
    /// Writes the checkpoint of step `stepsDone` if one is due. COLLECTIVE.
    void afterStep(std::int64_t stepsDone);
    /// Writes the checkpoint of step `stepsDone` now; returns its path. COLLECTIVE.
    std::string write(std::int64_t stepsDone);
    /// What writeTo wrote: the file's attributes and its size [bytes].
    struct Written : io::CheckpointInfo {
        std::uint64_t bytes = 0;
    };
    /// Writes the state after `stepsDone` steps in the checkpoint format to `path` (no
    /// rotation, no log line: a particle snapshot too). COLLECTIVE.
    Written writeTo(std::string const& path, std::int64_t stepsDone);
    /// Also store the state self-gravity keeps between updates (nullptr: none); `gravity`
    /// must outlive this object. Not collective.
    void setSelfGravity(coupling::SelfGravityForces const* gravity) { m_gravity = gravity; }

private:
    core::Comm const* m_comm;
    particles::LocalParticles const* m_local;
    coupling::SelfGravityForces const* m_gravity = nullptr;
    OutputSection m_output;
    double m_dt;
    domain::ForestSpec m_forest;
    std::string m_text;
    TimeAt m_timeAt;
    std::vector<std::string> m_written; ///< this run's checkpoints, oldest first (rank 0)
};

} // namespace regolith::apps
