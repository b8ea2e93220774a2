#include "apps/regolith/Checkpointing.hpp"

#include "apps/common/StateChecksum.hpp"
#include "apps/regolith/GravitySetup.hpp"
#include "apps/regolith/LoopSummary.hpp"
#include "apps/regolith/ParticleSetup.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/log/Log.hpp"
#include "core/mpi/AgreeOnInputError.hpp"
#include "io/checkpoint/CheckpointSeries.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/checkpoint/RestoreGrains.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <mpi.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace regolith::apps {

namespace {
/// The line between the scene file and its command-line overrides in sceneText.
constexpr std::string_view kCommandLineMarker = "# regolith command line:";
/// After it, a value "auto" chose (withAutoChoices): "# auto: key=value".
constexpr std::string_view kAutoPrefix = "# auto: ";
constexpr std::string_view kSetPrefix = "# --set ";

/// The lines after kCommandLineMarker that start with `prefix`, without it.
std::vector<std::string> linesAfterMarker(std::string const& text, std::string_view prefix) {
    std::vector<std::string> out;
    std::size_t const marker = text.rfind(fmt::format("\n{}", kCommandLineMarker));
    if (marker == std::string::npos)
        return out;
    std::string_view rest = std::string_view(text).substr(marker + 1);
    while (!rest.empty()) {
        std::size_t const end = rest.find('\n');
        std::string_view const line = rest.substr(0, end);
        rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
        if (line.starts_with(prefix))
            out.emplace_back(line.substr(prefix.size()));
    }
    return out;
}
} // namespace

std::string sceneText(core::AppContext const& ctx) {
    std::string text;
    if (ctx.isRoot()) {
        if (ctx.options.scenePath.empty()) {
            text = std::string(ctx.defaultScene);
        } else {
            std::ifstream in(ctx.options.scenePath);
            std::ostringstream s;
            s << in.rdbuf();
            text = s.str(); // the scene was read moments ago; an empty text only loses provenance
        }
        text += fmt::format("\n{}", kCommandLineMarker);
        for (std::string const& o : ctx.options.overrides)
            text += fmt::format("\n{}{}", kSetPrefix, o);
        if (ctx.options.steps)
            text += fmt::format("\n# --steps {}", *ctx.options.steps);
    }
    ctx.world.broadcast(text, 0);
    return text;
}

namespace {

std::string describe(core::AABB const& box, std::array<bool, 3> const& periodic) {
    return fmt::format("[{}, {}, {}] - [{}, {}, {}], periodic [{}]", box.min.x(), box.min.y(),
                       box.min.z(), box.max.x(), box.max.y(), box.max.z(),
                       fmt::join(periodic, ", "));
}

/// The scene a run's text stands for: the file, with the command-line overrides that
/// sceneText wrote after kCommandLineMarker ("# --set a.b=c" lines) and the values "auto"
/// chose ("# auto: a.b=c", withAutoChoices) applied; one that does not apply (a value with a
/// line break) is left out rather than losing the comparison. A text without the marker
/// (checkpoints before 2026-11-26) is the file alone.
core::ConfigTable effectiveScene(std::string const& text, std::string const& name) {
    std::size_t const marker = text.rfind(fmt::format("\n{}", kCommandLineMarker));
    std::string const file = marker == std::string::npos ? text : text.substr(0, marker);
    auto table = core::ConfigTable::fromString(file, name);
    for (std::string_view prefix : {kSetPrefix, kAutoPrefix})
        for (std::string const& assignment : linesAfterMarker(text, prefix)) {
            try {
                table.applyOverride(assignment);
            } catch (core::InputError const&) {
            }
        }
    return table;
}

/// The sections of the checkpoint's scene that differ from this run's, both with their
/// command-line overrides (output and time are expected to change on a restart, the keys of
/// SpeedChoices.hpp may). Empty if either does not parse.
std::vector<std::string> differingSections(std::string const& stored, std::string const& text) {
    try {
        auto a = effectiveScene(stored, "checkpoint scene");
        auto b = effectiveScene(text, "scene");
        // Keys that change the speed, not the trajectory (SpeedChoices.hpp): not compared.
        for (auto* table : {&a, &b})
            for (char const* same : {"sync.skin=0", "sync.subdomains=\"merged\""})
                table->applyOverride(same);
        std::vector<std::string> out;
        for (char const* key : {"name", "domain", "particles", "walls", "insert", "contact",
                                "gravity", "sync", "granular_gas", "dense_ramp", "bidisperse"})
            if (!a.sameValue(key, b))
                out.emplace_back(key);
        return out;
    } catch (core::InputError const&) {
        return {};
    }
}

} // namespace

void requireSameDomain(std::string const& path, io::CheckpointInfo const& info,
                       SceneDescription const& scene) {
    bool const sameDomain = info.domain.min == scene.forest.domain.min &&
                            info.domain.max == scene.forest.domain.max &&
                            info.periodic == scene.forest.periodic;
    if (!sameDomain)
        throw core::InputError(
            fmt::format("--restart {}: the checkpoint was written for the domain {}, the scene "
                        "has {}",
                        path, describe(info.domain, info.periodic),
                        describe(scene.forest.domain, scene.forest.periodic)));
}

std::string withAutoChoices(std::string text, std::vector<AutoChoice> const& choices) {
    for (AutoChoice const& c : choices)
        text += fmt::format("\n{}{}={}", kAutoPrefix, c.key, c.value);
    return text;
}

std::vector<AutoChoice> reuseAutoChoices(core::AppContext& ctx, SceneDescription& scene,
                                         std::string const& storedText) {
    // The keys each "auto" of this scene stands for (gravity.self = "auto" chose theta too
    // when it chose the tree).
    std::vector<std::string> keys;
    if (scene.time.dtAuto)
        keys.emplace_back("time.dt");
    if (scene.gravity.self == "auto")
        keys.insert(keys.end(), {"gravity.self", "gravity.theta"});
    if (scene.gravity.thresholdAuto)
        keys.insert(keys.end(), {"gravity.update_threshold", "gravity.update_every"});
    std::vector<AutoChoice> out;
    if (keys.empty())
        return out;
    for (std::string const& assignment : linesAfterMarker(storedText, kAutoPrefix)) {
        std::string const key = assignment.substr(0, assignment.find('='));
        if (std::find(keys.begin(), keys.end(), key) != keys.end())
            out.push_back({key, assignment.substr(key.size() + 1), "from the checkpoint"});
    }
    std::string missing;
    for (std::string const& key : keys)
        if (key != "gravity.theta" && key != "gravity.update_every" &&
            std::none_of(out.begin(), out.end(), [&](auto const& c) { return c.key == key; }))
            missing += " " + key;
    if (!missing.empty())
        throw core::InputError(fmt::format(
            "--restart {}: the checkpoint does not say what \"auto\" chose for{} (it was "
            "written before 2026-11-27, or by a run that set them); set the values the original "
            "run chose (its run summary lists them under \"auto\") with --set",
            ctx.options.restartPath, missing));
    for (AutoChoice const& c : out)
        ctx.scene.applyOverride(c.key + "=" + c.value, c.key + " (\"auto\" in the checkpoint)");
    scene = parseScene(ctx.scene, ctx.options.scenePath);
    return out;
}

void checkRestart(core::Comm const& comm, std::string const& path, io::CheckpointSlice const& slice,
                  SceneDescription const& scene, std::string const& sceneText) {
    io::CheckpointInfo const& info = slice.info;
    std::string const context = "--restart " + path;
    if (info.step > scene.time.steps)
        throw core::InputError(fmt::format("{}: the checkpoint is at step {}, beyond the scene's "
                                           "time.steps = {} (a total, not a remainder)",
                                           context, info.step, scene.time.steps));
    if (info.step == scene.time.steps) // --steps is a total, not a remainder
        core::log::warn("{}: the checkpoint is at step {}, the scene's time.steps (a total, not "
                        "a remainder): no step to run",
                        context, info.step);
    if (info.dt != scene.time.dt)
        core::log::warn("{}: the checkpoint was written with time.dt = {}, the scene has {}",
                        context, info.dt, scene.time.dt);
    if (auto const differ = differingSections(info.scene, sceneText); !differ.empty())
        core::log::warn("{}: the checkpoint was written by another scene (it differs in {}): the "
                        "grains, their contact history and the self-gravity state come from the "
                        "checkpoint, everything else from this scene",
                        context, fmt::join(differ, ", "));
    // The contact model's tables are indexed by type without a check (the contact loop).
    std::size_t const types = materialTypeCount(scene);
    core::agreeOnInputError(comm, [&] {
        for (io::GrainState const& g : slice.grains)
            if (g.type >= types)
                throw core::InputError(fmt::format(
                    "{}: grain uid {} has material type {}, but the scene's [[particles]] and "
                    "[[walls]] name types up to {} only (the checkpoint was written for another "
                    "scene)",
                    context, g.uid, g.type, types - 1));
    });
}

void restoreSelfGravity(io::CheckpointSlice const& slice,
                        coupling::SelfGravityForces& selfGravity) {
    std::vector<particles::Uid> uid;
    std::vector<gravity::GrainRecord> records;
    uid.reserve(slice.grains.size());
    records.reserve(slice.grains.size());
    for (io::GrainState const& g : slice.grains) {
        uid.push_back(g.uid);
        gravity::GrainRecord r;
        for (int k = 0; k < 3; ++k) {
            r.reference[static_cast<std::size_t>(k)] = g.gravityReference[k];
            r.field[static_cast<std::size_t>(k)] = g.gravityField[k];
            r.slope[static_cast<std::size_t>(k)] = g.gravitySlope[k];
        }
        records.push_back(r); // NaN rows (no record) are skipped by the policy
    }
    selfGravity.restore({slice.info.gravityUpdates, slice.info.gravityPotentialEnergy,
                         slice.info.gravitySinceUpdate, slice.info.gravityInterval},
                        uid, records);
}

CheckpointSchedule::CheckpointSchedule(core::Comm const& comm, SceneDescription const& scene,
                                       std::string text, particles::LocalParticles const& local,
                                       TimeAt timeAt)
    : m_comm(&comm)
    , m_local(&local)
    , m_output(scene.output)
    , m_dt(scene.time.dt)
    , m_forest(scene.forest)
    , m_text(std::move(text))
    , m_timeAt(std::move(timeAt)) {
    if (m_output.checkpointEvery <= 0)
        return;
    std::string failure;
    if (comm.rank() == 0) {
        std::error_code ec;
        std::filesystem::create_directories(m_output.dir, ec);
        if (ec)
            failure = fmt::format("output.dir = \"{}\": cannot create the directory for "
                                  "checkpoints: {}",
                                  m_output.dir, ec.message());
    }
    comm.broadcast(failure, 0);
    if (!failure.empty())
        throw core::InputError(failure);
}

void CheckpointSchedule::afterStep(std::int64_t stepsDone) {
    if (due(stepsDone))
        write(stepsDone);
}

void CheckpointSchedule::checkReplaced(std::int64_t firstStep, std::int64_t lastStep) const {
    if (m_output.checkpointEvery <= 0)
        return;
    std::string failure;
    if (m_comm->rank() == 0) {
        auto const names =
            io::checkpointsToReplace(m_output.dir, m_output.checkpointEvery, firstStep, lastStep);
        for (std::string const& name : names) {
            std::string const why =
                io::notACheckpointFile((std::filesystem::path(m_output.dir) / name).string());
            if (!why.empty()) {
                failure = fmt::format("output.dir = \"{}\" holds '{}', {}: this run writes its "
                                      "checkpoint there; remove or rename it, or choose another "
                                      "output.dir",
                                      m_output.dir, name, why);
                break;
            }
        }
        if (failure.empty() && !names.empty())
            core::log::warn("output.dir = \"{}\" holds {} checkpoint(s) of the steps this run "
                            "writes ({}{}), an earlier run's: they will be replaced",
                            m_output.dir, names.size(), names.front(),
                            names.size() > 1 ? fmt::format(" ... {}", names.back()) : "");
    }
    m_comm->broadcast(failure, 0);
    if (!failure.empty())
        throw core::InputError(failure);
}

std::string CheckpointSchedule::write(std::int64_t stepsDone) {
    std::string const path = io::checkpointPath(m_output.dir, stepsDone);
    double const start = MPI_Wtime();
    Written const info = writeTo(path, stepsDone);
    double const seconds = MPI_Wtime() - start; // rank 0 renamed last: the whole write
    if (m_comm->rank() == 0) {
        m_written.push_back(path);
        io::rotateCheckpoints(m_written, m_output.checkpointKeep);
    }
    core::log::info("checkpoint {}: {} grains, {} history entries, {:.3g} MB in {:.3g} s", path,
                    info.grainCount, info.historyCount, static_cast<double>(info.bytes) * 1e-6,
                    seconds);
    return path;
}

CheckpointSchedule::Written CheckpointSchedule::writeTo(std::string const& path,
                                                        std::int64_t stepsDone) {
    Written info;
    info.step = stepsDone;
    info.time = m_timeAt(stepsDone);
    info.dt = m_dt;
    info.domain = m_forest.domain;
    info.periodic = m_forest.periodic;
    info.scene = m_text;
    info.stateChecksum = stateChecksumFrom(*m_comm, masterSource(*m_local));
    auto grains = io::collectMasters(*m_local);
    if (m_gravity != nullptr) {
        coupling::SelfGravityState const s = m_gravity->state();
        info.gravityUpdates = s.updates;
        info.gravityPotentialEnergy = s.potentialEnergy;
        info.gravitySinceUpdate = s.sinceUpdate;
        info.gravityInterval = s.interval;
        for (io::GrainState& g : grains)
            if (gravity::GrainRecord const* r = m_gravity->record(g.uid)) {
                g.gravityReference = core::Vec3(r->reference[0], r->reference[1], r->reference[2]);
                g.gravityField = core::Vec3(r->field[0], r->field[1], r->field[2]);
                g.gravitySlope = core::Vec3(r->slope[0], r->slope[1], r->slope[2]);
            }
    }
    info.bytes = io::writeCheckpoint(*m_comm, path, info, grains);
    return info;
}

RunStart restoreState(core::AppContext const& ctx, SceneDescription const& scene,
                      std::string const& text, io::CheckpointSlice slice, double started,
                      particles::LocalParticles& local) {
    std::string const& path = ctx.options.restartPath;
    checkRestart(ctx.world, path, slice, scene, text);
    io::restoreGrains(ctx.world, local, slice.grains, "--restart " + path);
    std::string const restored = stateChecksumFrom(ctx.world, masterSource(local));
    if (restored != slice.info.stateChecksum)
        throw core::InputError(fmt::format("--restart {}: the restored state has checksum {}, "
                                           "the checkpoint says {}",
                                           path, restored, slice.info.stateChecksum));
    warnSelfGravityParameters(ctx.world, local, scene); // a restart may change G, dt, k ...
    double const seconds = ctx.world.allReduce(MPI_Wtime() - started, core::ReduceOp::Max);
    core::log::info("restarting from {} at step {} (time {}): {} grains, {} contact-history "
                    "entries, read and distributed in {:.3g} s",
                    path, slice.info.step, slice.info.time, slice.info.grainCount,
                    slice.info.historyCount, seconds);
    return {slice.info.step, slice.info.time, std::move(slice)};
}

} // namespace regolith::apps
