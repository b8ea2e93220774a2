#include "io/vtk/VtkOutput.hpp"

#include "core/Error.hpp"
#include "core/file/Files.hpp"
#include "core/log/Log.hpp"
#include "core/mpi/AgreeOnInputError.hpp"
#include "io/vtk/GridPieces.hpp"
#include "io/vtk/VtkPieces.hpp"
#include "io/vtk/VtkSeries.hpp"
#include "io/vtk/WallPieces.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string_view>
#include <system_error>

namespace regolith::io {

namespace fs = std::filesystem;

namespace {

std::string pvdText(std::vector<std::pair<double, std::string>> const& steps) {
    std::string out = "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                      "  <Collection>\n";
    for (auto const& [time, file] : steps)
        out += fmt::format(
            "    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, file);
    out += "  </Collection>\n</VTKFile>\n";
    return out;
}

/// The entries of an existing series before `time`, or up to it with `inclusive` (a restart
/// continues it).
std::vector<std::pair<double, std::string>> keptEntries(std::string const& pvd, double time,
                                                        bool inclusive = false) {
    std::vector<std::pair<double, std::string>> out;
    if (time == -std::numeric_limits<double>::infinity() || !fs::is_regular_file(pvd))
        return out;
    for (SeriesEntry const& e : readSeries(pvd))
        if (e.time < time || (inclusive && e.time == time))
            out.emplace_back(e.time, e.file);
    return out;
}

/// Whether the file at `pvd` is a series this program writes: a VTK collection each of whose
/// data sets is "vtk/<kind>_<digits>.<extension>" (also none).
bool isOwnSeries(std::string const& pvd, std::string_view kind, std::string_view extension) {
    if (!core::whyNotRegularFile(pvd).empty())
        return false;
    std::string const prefix = fmt::format("vtk/{}_", kind);
    std::string const suffix = fmt::format(".{}", extension);
    try {
        for (SeriesEntry const& e : readSeries(pvd)) {
            std::string_view const f = e.file;
            if (!f.starts_with(prefix) || !f.ends_with(suffix) ||
                f.size() == prefix.size() + suffix.size())
                return false;
            std::string_view const digits =
                f.substr(prefix.size(), f.size() - prefix.size() - suffix.size());
            if (digits.find_first_not_of("0123456789") != std::string_view::npos)
                return false;
        }
    } catch (core::InputError const&) {
        return false;
    }
    return true;
}

} // namespace

VtkOutput::VtkOutput(core::Comm const& comm, VtkOptions options)
    : m_comm(&comm)
    , m_options(std::move(options)) {
    core::agreeOnInputError(comm, [&] {
        if (comm.rank() != 0)
            return;
        std::error_code ec;
        fs::create_directories(fs::path(m_options.dir) / "vtk", ec);
        if (ec)
            throw core::InputError(fmt::format(
                "output.dir = \"{}\": cannot create '{}' for "
                "the VTK output: {}",
                m_options.dir, (fs::path(m_options.dir) / "vtk").string(), ec.message()));
        // Only a series this program writes is replaced or removed: anything else under its
        // name is the user's, refused before the first step.
        struct Series {
            std::string path;
            char const* kind;
            char const* extension;
            bool written;
        };
        for (Series const& s : {Series{particleSeriesPath(), "particles", "pvtu", true},
                                Series{blockSeriesPath(), "blocks", "pvtu", m_options.blocks},
                                Series{gridSeriesPath(), "grid", "vtm", m_options.writesGrid},
                                Series{wallSeriesPath(), "walls", "vtp", m_options.writesWalls}})
            if (s.written && fs::exists(fs::symlink_status(s.path, ec)) &&
                !isOwnSeries(s.path, s.kind, s.extension))
                throw core::InputError(fmt::format(
                    "output.dir = \"{}\" holds '{}', which is not a {} series this program "
                    "writes: this run writes its {} series there; remove or rename it, or choose "
                    "another output.dir",
                    m_options.dir, fs::path(s.path).filename().string(), s.kind, s.kind));
        m_particleSteps = keptEntries(particleSeriesPath(), m_options.keepEntriesBefore);
        m_blockSteps = keptEntries(blockSeriesPath(), m_options.keepEntriesBefore);
        // A restart writes no grid at its first step (the field is restored per grain, not
        // on the grid): the original run's entry of that step stays.
        m_gridSteps = keptEntries(gridSeriesPath(), m_options.keepEntriesBefore, true);
        if (m_options.writesWalls)
            m_wallSteps = keptEntries(wallSeriesPath(), m_options.keepEntriesBefore);
        bool const fresh = m_options.keepEntriesBefore == -std::numeric_limits<double>::infinity();
        if (fresh && !m_options.writesGrid && fs::exists(gridSeriesPath(), ec)) {
            if (!isOwnSeries(gridSeriesPath(), "grid", "vtm"))
                core::log::warn("'{}' is not a grid series this program writes: left alone",
                                gridSeriesPath());
            else if (fs::remove(gridSeriesPath(), ec); ec)
                core::log::warn("cannot remove '{}', an earlier run's grid series (this run writes "
                                "no grid): {}",
                                gridSeriesPath(), ec.message());
            else
                core::log::warn("removed '{}', an earlier run's grid series: this run writes no "
                                "grid (the pieces in '{}' stay)",
                                gridSeriesPath(), (fs::path(m_options.dir) / "vtk").string());
        }
    });
}

std::string VtkOutput::particleSeriesPath() const {
    return (fs::path(m_options.dir) / "particles.pvd").string();
}

std::string VtkOutput::blockSeriesPath() const {
    return (fs::path(m_options.dir) / "blocks.pvd").string();
}

std::string VtkOutput::gridSeriesPath() const {
    return (fs::path(m_options.dir) / "grid.pvd").string();
}

std::string VtkOutput::wallSeriesPath() const {
    return (fs::path(m_options.dir) / "walls.pvd").string();
}

void VtkOutput::writeWalls(std::int64_t step, double time, particles::WallList const& walls,
                           core::AABB const& domain) {
    core::agreeOnInputError(*m_comm, [&] {
        if (m_comm->rank() != 0)
            return;
        std::string const file = fmt::format("walls_{:08d}.vtp", step);
        try {
            detail::WallMesh const mesh = detail::wallMesh(walls, domain);
            core::replaceFile((fs::path(m_options.dir) / "vtk" / file).string(),
                              [&](std::string const& tmp) { detail::writeWallPiece(tmp, mesh); });
        } catch (core::InputError const&) {
            throw;
        } catch (core::Error const& e) {
            throw core::InputError(e.what());
        }
        m_wallSteps.emplace_back(time, "vtk/" + file);
        core::replaceFileWith(wallSeriesPath(), pvdText(m_wallSteps));
    });
}

namespace {

std::string gridPiece(std::int64_t step, std::uint64_t curveIndex) {
    return fmt::format("grid_{:08d}_b{:06d}.vti", step, curveIndex);
}

} // namespace

void VtkOutput::write(std::int64_t step, double time, particles::LocalParticles const& local,
                      std::optional<gravity::GridFieldsView> const& grid) {
    if (grid && !m_gridBlocksKnown) {
        // The forest is static: every rank learns every block's curve index once.
        std::vector<std::uint64_t> mine;
        for (domain::Block const& b : grid->layout->forest().blocks())
            mine.push_back(b.curveIndex);
        m_gridBlocks = m_comm->allGatherVarying<std::uint64_t>(mine);
        std::sort(m_gridBlocks.begin(), m_gridBlocks.end());
        m_gridBlocksKnown = true;
    }
    fs::path const vtkDir = fs::path(m_options.dir) / "vtk";
    auto const piece = [&](char const* kind, int rank) {
        return fmt::format("{}_{:08d}_r{:04d}.vtu", kind, step, rank);
    };
    std::string const particleIndex = fmt::format("particles_{:08d}.pvtu", step);
    std::string const blockIndex = fmt::format("blocks_{:08d}.pvtu", step);
    core::agreeOnInputError(*m_comm, [&] {
        try {
            // Each piece through a fresh temporary: a link under its name is replaced, not
            // written through.
            core::replaceFile((vtkDir / piece("particles", m_comm->rank())).string(),
                              [&](std::string const& tmp) {
                                  detail::writeParticlePiece(tmp, local, m_options.shadows);
                              });
            if (m_options.blocks)
                core::replaceFile(
                    (vtkDir / piece("blocks", m_comm->rank())).string(),
                    [&](std::string const& tmp) { detail::writeBlockPiece(tmp, local); });
            if (grid) {
                auto const& blocks = grid->layout->forest().blocks();
                for (std::size_t b = 0; b < blocks.size(); ++b)
                    core::replaceFile(
                        (vtkDir / gridPiece(step, blocks[b].curveIndex)).string(),
                        [&](std::string const& tmp) { detail::writeGridPiece(tmp, *grid, b); });
            }
        } catch (core::InputError const&) {
            throw;
        } catch (core::Error const& e) {
            throw core::InputError(e.what()); // a full disk is the user's to fix
        }
    });
    // Rank 0 writes the indices after every piece exists (the agreement above is a barrier).
    core::agreeOnInputError(*m_comm, [&] {
        if (m_comm->rank() != 0)
            return;
        std::vector<std::string> particlePieces;
        std::vector<std::string> blockPieces;
        for (int r = 0; r < m_comm->size(); ++r) {
            particlePieces.push_back(piece("particles", r));
            blockPieces.push_back(piece("blocks", r));
        }
        core::replaceFileWith(
            (vtkDir / particleIndex).string(),
            detail::pvtuText(detail::particleArrays(m_options.shadows), {}, particlePieces));
        m_particleSteps.emplace_back(time, "vtk/" + particleIndex);
        core::replaceFileWith(particleSeriesPath(), pvdText(m_particleSteps));
        if (m_options.blocks) {
            core::replaceFileWith((vtkDir / blockIndex).string(),
                                  detail::pvtuText({}, detail::blockArrays(), blockPieces));
            m_blockSteps.emplace_back(time, "vtk/" + blockIndex);
            core::replaceFileWith(blockSeriesPath(), pvdText(m_blockSteps));
        }
        if (grid) {
            std::vector<detail::BlockPiece> gridPieces;
            for (std::uint64_t const c : m_gridBlocks)
                gridPieces.push_back({fmt::format("block {}", c), gridPiece(step, c)});
            std::string const gridIndex = fmt::format("grid_{:08d}.vtm", step);
            core::replaceFileWith((vtkDir / gridIndex).string(), detail::vtmText(gridPieces));
            std::erase_if(m_gridSteps, [&](auto const& e) { return e.first == time; });
            m_gridSteps.emplace_back(time, "vtk/" + gridIndex);
            core::replaceFileWith(gridSeriesPath(), pvdText(m_gridSteps));
        }
    });
}

} // namespace regolith::io
