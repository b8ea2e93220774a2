#pragma once
/// The progress of a run on rank 0's standard output (docs/guide/parallel.md): on a terminal a
/// live line redrawn in place (at most 5 times a second), otherwise, e.g. in a log file, one
/// line every output.progress_seconds; nothing with --quiet.
///
///     step 1200/5000  t = 12  850 steps/s  ETA 4.5 s  3937 grains  sync hybrid  gravity none
///
/// followed, once the run has measured it, by the median and 99th percentile of the self-gravity
/// force error over the run (gravity.check_every), "force error 0.0012 (p99 0.0051)", and on
/// more than one rank by the last measured load imbalance (DynamicBalance.hpp),
/// "imbalance 1.04".
#include "gravity/common/ForceError.hpp"

#include <cstdint>
#include <string>

namespace regolith::apps {

struct ProgressSettings {
    std::int64_t firstStep = 0; ///< steps done when the loop starts (a restart's step)
    double firstTime = 0.0;     ///< simulated time then [time]
    std::int64_t lastStep = 0;  ///< time.steps
    double dt = 0.0;            ///< [time]
    std::int64_t grains = 0;    ///< masters at the start, over all ranks
    std::string sync;           ///< synchronisation method
    std::string gravity;        ///< self-gravity method
    int ranks = 1;              ///< the run's ranks
    double logSeconds = 10.0;   ///< interval of log lines when not on a terminal; <= 0: none
    bool enabled = true;        ///< false on ranks other than 0 and with --quiet
};

class ProgressLine {
public:
    /// Decides once whether standard output is a terminal a person watches (a tty with a window
    /// size; not Open MPI's pty). Not collective.
    explicit ProgressLine(ProgressSettings settings);
    /// After each step: prints if it is time to. Not collective (rank 0 alone prints).
    void afterStep(std::int64_t stepsDone);
    /// The load imbalance (max / mean) the line shows from now on. Not collective.
    void setImbalance(double imbalance) { m_imbalance = imbalance; }
    /// The measured force error the line shows from now on, after `checks` > 0 checks. Not
    /// collective.
    void setForceError(gravity::ErrorStats const& error, long long checks) {
        m_forceError = error;
        m_forceChecks = checks;
    }
    /// Grains added during the run (inserted), over all ranks: the line counts them from now
    /// on. Not collective.
    void addGrains(std::int64_t added) { m_settings.grains += added; }
    /// Ends the live line (a newline, so that what follows starts on its own line).
    void finish();
    /// Erases the live line before other output (a log line) is printed; the next
    /// afterStep draws it again. Not collective.
    void clear();

    /// The text of the line after `stepsDone` steps, `elapsed` seconds after the loop
    /// started. Not collective.
    [[nodiscard]] std::string text(std::int64_t stepsDone, double elapsed) const;

private:
    ProgressSettings m_settings;
    bool m_terminal = false;
    bool m_drawn = false;
    double m_start = 0.0;
    double m_lastPrint = 0.0;
    double m_imbalance = 1.0;
    gravity::ErrorStats m_forceError;
    long long m_forceChecks = 0;
};

} // namespace regolith::apps
