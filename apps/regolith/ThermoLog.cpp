#include "apps/regolith/ThermoLog.hpp"

#include "core/Error.hpp"
#include "core/file/Files.hpp"
#include "core/log/Log.hpp"
#include "core/mpi/AgreeOnInputError.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdio>
#include <sstream>

namespace regolith::apps {

namespace {

/// The text of `value` in column `c`: integers whole, others with every significant digit
/// (a row read back gives the measured value bit for bit), or 6 digits on standard output.
std::string cell(ThermoColumn const& c, ThermoSample const& s, bool full) {
    double const value = c.value(s);
    if (c.integer)
        return fmt::format("{}", static_cast<long long>(value));
    return full ? fmt::format("{:.17g}", value) : fmt::format("{:.6g}", value);
}

/// The step of a row of thermo.csv (its first field), or -1 if it has none.
long long stepOf(std::string const& row) {
    long long step = -1;
    auto const end = row.find(',');
    auto const [p, ec] = std::from_chars(row.data(), row.data() + std::min(end, row.size()), step);
    return ec == std::errc{} && p == row.data() + std::min(end, row.size()) ? step : -1;
}

/// The file's header and the rows of an earlier run up to `lastStep`, from `path` if it
/// holds thermo output with the same columns, `headerLine` (else the header alone, with a
/// warning).
std::string keptRows(std::string const& path, std::int64_t lastStep,
                     std::string const& headerLine) {
    std::string const header = headerLine + "\n";
    if (!core::whyNotRegularFile(path).empty())
        return header;
    std::ifstream in(path);
    std::string line;
    if (!std::getline(in, line) || line + "\n" != header) {
        core::log::warn("{}: not the thermo output of this version (another header): the rows "
                        "before the restart are not kept",
                        path);
        return header;
    }
    std::string kept = header;
    while (std::getline(in, line)) {
        long long const step = stepOf(line);
        if (step >= 0 && step <= lastStep)
            kept += line + "\n";
    }
    return kept;
}

} // namespace

std::string ThermoLog::header() const {
    std::string h;
    for (ThermoColumn const& c : m_columns) {
        if (!h.empty())
            h += ',';
        h += c.name;
    }
    return h;
}

ThermoLog::ThermoLog(core::Comm const& comm, ThermoSettings settings)
    : m_settings(std::move(settings))
    , m_columns(thermoColumns(m_settings.walls))
    , m_root(comm.rank() == 0) {
    if (m_settings.every <= 0)
        return;
    core::agreeOnInputError(comm, [&] {
        if (!m_root)
            return;
        std::string const& path = m_settings.path;
        core::replaceFileWith(path, m_settings.restart
                                        ? keptRows(path, m_settings.firstStep, header())
                                        : header() + "\n");
        m_file.open(path, std::ios::app);
        if (!m_file)
            throw core::InputError(fmt::format("cannot append to '{}'", path));
    });
}

void ThermoLog::write(ThermoSample const& sample) {
    if (!m_root || m_settings.every <= 0)
        return;
    auto const& columns = m_columns;
    if (m_file.is_open()) {
        std::string row;
        for (ThermoColumn const& c : columns) {
            if (!row.empty())
                row += ',';
            row += cell(c, sample, true);
        }
        m_file << row << '\n';
        m_file.flush();
        if (!m_file) {
            core::log::warn("cannot write to '{}': thermo output stops here (step {})",
                            m_settings.path, sample.step);
            m_file.close();
        }
    }
    if (!m_settings.print)
        return;
    std::string line;
    if (!m_headingPrinted) {
        for (ThermoColumn const& c : columns)
            line += fmt::format("{:>{}}", c.name, c.integer ? 9 : 13);
        line += '\n';
        m_headingPrinted = true;
    }
    for (ThermoColumn const& c : columns)
        line += fmt::format("{:>{}}", cell(c, sample, false), c.integer ? 9 : 13);
    fmt::print("{}\n", line);
    std::fflush(stdout);
}

} // namespace regolith::apps
