#pragma once
/// What a `regolith` run does between its steps, as observers of the coupled run (in this
/// order after a step): a thermo row, grains poured in, a checkpoint, VTK files, a particle
/// snapshot, the load balance, the progress line. Each is due on its own schedule; a step
/// none of the first five looks at ends open (coupling::Simulation).
#include "apps/common/RunSummary.hpp"
#include "apps/regolith/Checkpointing.hpp"
#include "apps/regolith/DynamicBalance.hpp"
#include "apps/regolith/GrainPouring.hpp"
#include "apps/regolith/ParticleSnapshots.hpp"
#include "apps/regolith/ProgressLine.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/regolith/ThermoLog.hpp"
#include "core/app/RunApp.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "io/vtk/VtkOutput.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace regolith::apps {

/// Where the run's steps start: a new run's step 0 at time 0, or a checkpoint's.
struct RunOrigin {
    std::int64_t step = 0;
    double time = 0.0;
    bool restart = false;
    std::string sceneText;   ///< stored in the checkpoints (with the "auto" choices)
    std::int64_t grains = 0; ///< masters at the start, over all ranks
};

class RunOutputs {
public:
    /// Opens the outputs of `scene` (output.dir, thermo.csv, the VTK series) and writes the
    /// start's frame, thermo row and snapshot for a new run (a restart has them from before).
    /// `sim` has started or resumed and must outlive this object, as must `scene`. Throws
    /// core::InputError on every rank if an output cannot be written. COLLECTIVE.
    RunOutputs(core::AppContext const& ctx, SceneDescription const& scene,
               coupling::Simulation& sim, RunOrigin const& origin);

    /// Adds the observers to `sim` (the one given to the constructor).
    void observe(coupling::Simulation& sim);
    /// After the last step: ends the progress line and measures the final imbalance for the
    /// summary. COLLECTIVE.
    [[nodiscard]] RunSummary::Balance finish();
    [[nodiscard]] std::int64_t inserted() const { return m_pouring.inserted(); }

private:
    [[nodiscard]] double timeAt(std::int64_t step) const;
    void writeVtk(std::int64_t step);
    void writeThermo(std::int64_t stepsDone);
    /// After grains moved between ranks: what stands on the old assignment. COLLECTIVE.
    void relocate();

    core::Comm const* m_comm;
    SceneDescription const* m_scene;
    coupling::Simulation* m_sim;
    RunOrigin m_origin;
    CheckpointSchedule m_checkpoints;
    ParticleSnapshots m_snapshots;
    std::optional<io::VtkOutput> m_vtk;
    ProgressLine m_progress;
    DynamicBalance m_balance;
    GrainPouring m_pouring;
    ThermoLog m_thermo;
};

} // namespace regolith::apps
