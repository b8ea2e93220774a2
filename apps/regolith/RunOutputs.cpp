#include "apps/regolith/RunOutputs.hpp"

#include "apps/regolith/LoopSummary.hpp"
#include "apps/regolith/RunPaths.hpp"
#include "apps/regolith/ThermoSample.hpp"

#include <utility>

namespace regolith::apps {

namespace {

/// The grid fields for VTK output: those of grid gravity once computed, else none.
std::optional<gravity::GridFieldsView> gridFieldsOf(coupling::SelfGravityForces const* gravity) {
    return gravity != nullptr ? gravity->gridFields() : std::nullopt;
}

} // namespace

RunOutputs::RunOutputs(core::AppContext const& ctx, SceneDescription const& scene,
                       coupling::Simulation& sim, RunOrigin const& origin)
    : m_comm(&ctx.world)
    , m_scene(&scene)
    , m_sim(&sim)
    , m_origin(origin)
    , m_checkpoints(ctx.world, scene, origin.sceneText, sim.grains(),
                    [this](std::int64_t step) { return timeAt(step); })
    , m_snapshots(ctx.world, scene.output, sim.grains(), m_checkpoints)
    , m_progress(ProgressSettings{origin.step, origin.time, scene.time.steps, scene.time.dt,
                                  origin.grains, std::string(toString(scene.sync.method)),
                                  scene.gravity.self, ctx.world.size(),
                                  scene.output.progressSeconds, ctx.isRoot() && !ctx.options.quiet})
    , m_balance(ctx.world, scene, sim.placement(), origin.step,
                {[this] { return m_sim->dem().contactsOfLastPass(); },
                 [this] { m_sim->dem().completeStep(); }, [this] { relocate(); }})
    , m_pouring(ctx.world, scene, sim.grains())
    , m_thermo(ctx.world, {thermoPath(scene), scene.output.thermoEvery, origin.step, origin.restart,
                           ctx.isRoot() && !ctx.options.quiet, sim.dem().walls().size()}) {
    m_checkpoints.setSelfGravity(sim.selfGravity());
    m_checkpoints.checkReplaced(origin.step, scene.time.steps);
    if (!origin.restart && m_snapshots.due(origin.step))
        m_snapshots.write(origin.step);
    if (scene.output.vtkEvery > 0) {
        // A restart continues the series of the run it restarts (the entries before it).
        io::VtkOptions options{scene.output.dir, scene.output.vtkShadows, true};
        if (origin.restart)
            options.keepEntriesBefore = origin.time;
        options.writesGrid = gridFieldsOf(sim.selfGravity()).has_value();
        options.writesWalls = !sim.dem().walls().empty();
        m_vtk.emplace(ctx.world, options);
        writeVtk(origin.step);
    }
    if (!origin.restart && m_thermo.due(origin.step))
        writeThermo(origin.step);
}

double RunOutputs::timeAt(std::int64_t step) const {
    return m_origin.time + static_cast<double>(step - m_origin.step) * m_scene->time.dt;
}

void RunOutputs::writeVtk(std::int64_t step) {
    particles::WallList const& walls = m_sim->dem().walls();
    m_vtk->write(step, timeAt(step), m_sim->grains(), gridFieldsOf(m_sim->selfGravity()));
    if (!walls.empty())
        m_vtk->writeWalls(step, timeAt(step), walls, m_sim->forest().geometry().domain());
}

void RunOutputs::writeThermo(std::int64_t stepsDone) {
    coupling::SelfGravityForces const* gravity = m_sim->selfGravity();
    m_thermo.write(measureThermo(*m_comm, m_sim->grains(), m_sim->dem().contacts(),
                                 {stepsDone, timeAt(stepsDone), m_scene->gravity.external,
                                  gravity ? gravity->stats().potentialEnergy : 0.0,
                                  m_balance.imbalance(), &m_sim->dem().walls()}));
}

void RunOutputs::relocate() {
    m_sim->relocated();
    if (m_sim->selfGravity() && m_vtk) // the grid output until the next update
        m_sim->selfGravity()->refreshGridFields(m_sim->grains());
}

void RunOutputs::observe(coupling::Simulation& sim) {
    using Needs = coupling::Simulation::ObserverNeeds;
    // First: the step's contacts index the grains as they lie, before an insertion or a
    // rebalance moves them.
    sim.addObserver([this](std::int64_t s) { return m_thermo.due(s); },
                    [this](coupling::Simulation& run) {
                        m_progress.clear(); // the row gets a line of its own
                        writeThermo(run.stepsDone());
                    },
                    Needs{.completeGrains = true, .contacts = true});
    sim.addObserver(
        [this](std::int64_t s) { return m_pouring.due(s); },
        [this](coupling::Simulation& run) {
            m_progress.clear(); // a grain that found no place is warned about
            std::int64_t const before = m_pouring.inserted();
            if (m_pouring.afterStep(run.stepsDone(), run.placement(), run.dem().walls()))
                relocate();
            m_progress.addGrains(m_pouring.inserted() - before);
        },
        {});
    sim.addObserver([this](std::int64_t s) { return m_checkpoints.due(s); },
                    [this](coupling::Simulation& run) {
                        m_progress.clear(); // the log line gets a line of its own
                        m_checkpoints.afterStep(run.stepsDone());
                    },
                    {});
    if (m_vtk)
        sim.addObserver(m_scene->output.vtkEvery,
                        [this](coupling::Simulation& run) { writeVtk(run.stepsDone()); });
    sim.addObserver([this](std::int64_t s) { return m_snapshots.due(s); },
                    [this](coupling::Simulation& run) { m_snapshots.write(run.stepsDone()); }, {});
    sim.addObserver([this](std::int64_t s) { return m_balance.due(s); },
                    [this](coupling::Simulation& run) { m_balance.afterStep(run.stepsDone()); },
                    Needs{.completeGrains = false, .contacts = false});
    // Every step, the grains as they are: the line reads only the step count and the
    // measurements above.
    sim.addObserver([](std::int64_t) { return true; },
                    [this](coupling::Simulation& run) {
                        m_progress.setImbalance(m_balance.imbalance());
                        if (coupling::SelfGravityForces const* g = run.selfGravity())
                            m_progress.setForceError(g->measuredError().stats(),
                                                     g->measuredError().checks());
                        m_progress.afterStep(run.stepsDone());
                    },
                    Needs{.completeGrains = false, .contacts = false});
}

RunSummary::Balance RunOutputs::finish() {
    m_progress.finish();
    return m_balance.finish();
}

} // namespace regolith::apps
