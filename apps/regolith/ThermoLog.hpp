#pragma once
/// The thermo output (output.thermo_every): a row of ThermoSample's columns every N steps in
/// output.dir/thermo.csv and, unless --quiet, as a line on standard output (rank 0). The file
/// is created through a temporary renamed into place (core::replaceFile), then appended to and
/// flushed row by row, so a run that stops leaves every row written so far; a restart keeps
/// the rows of the steps up to its checkpoint's and continues after them.
#include "apps/regolith/ThermoSample.hpp"
#include "core/mpi/Comm.hpp"

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace regolith::apps {

struct ThermoSettings {
    std::string path;           ///< output.dir/thermo.csv
    std::int64_t every = 0;     ///< output.thermo_every; 0: no thermo output
    std::int64_t firstStep = 0; ///< the loop's first step (a restart's checkpoint step)
    bool restart = false;       ///< keep the rows of an existing file up to firstStep
    bool print = true;          ///< standard output too (rank 0 without --quiet)
    std::size_t walls = 0;      ///< the run's walls: a force column triple each
};

class ThermoLog {
public:
    /// Writes the header (a new run) or the kept rows (a restart) to the file. Throws
    /// core::InputError on every rank if it cannot be written. COLLECTIVE.
    ThermoLog(core::Comm const& comm, ThermoSettings settings);

    /// Whether a row is due after `stepsDone` steps.
    [[nodiscard]] bool due(std::int64_t stepsDone) const {
        return m_settings.every > 0 && stepsDone % m_settings.every == 0;
    }
    /// Appends the row of `sample` (rank 0; a failed write is warned about once and ends
    /// the file's rows). Not collective.
    void write(ThermoSample const& sample);
    /// The header line of thermo.csv (the column names, comma-separated, no newline).
    [[nodiscard]] std::string header() const;

private:
    ThermoSettings m_settings;
    std::vector<ThermoColumn> m_columns;
    bool m_root = false;
    bool m_headingPrinted = false;
    std::ofstream m_file;
};

} // namespace regolith::apps
