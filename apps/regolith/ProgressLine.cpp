#include "apps/regolith/ProgressLine.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <sys/ioctl.h>
#include <unistd.h>
#include <utility>

namespace regolith::apps {

namespace {

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

std::string duration(double seconds) {
    if (seconds < 120.0)
        return fmt::format("{:.1f} s", seconds);
    if (seconds < 7200.0)
        return fmt::format("{:.1f} min", seconds / 60.0);
    return fmt::format("{:.1f} h", seconds / 3600.0);
}

constexpr double kTerminalRedrawSeconds = 0.2;

/// A terminal a person watches: a tty with a window size. Open MPI gives every rank a pseudo
/// terminal for stdout even when mpiexec's own output goes to a file (open-mpi/ompi#7868),
/// but that pty has no window size (0 columns, open-mpi/ompi#7900): such a rank writes log
/// lines, so a log never fills with redrawn lines. (Under mpiexec on a real terminal this
/// also gives log lines: the rank cannot tell the two apart.)
bool watchedTerminal() {
    winsize size{};
    return ::isatty(STDOUT_FILENO) == 1 && ::ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 &&
           size.ws_col > 0;
}

} // namespace

ProgressLine::ProgressLine(ProgressSettings settings)
    : m_settings(std::move(settings))
    , m_terminal(m_settings.enabled && watchedTerminal())
    , m_start(now())
    , m_lastPrint(m_start) {}

std::string ProgressLine::text(std::int64_t stepsDone, double elapsed) const {
    auto const done = static_cast<double>(stepsDone - m_settings.firstStep);
    auto const left = static_cast<double>(m_settings.lastStep - stepsDone);
    double const rate = elapsed > 0.0 ? done / elapsed : 0.0;
    std::string const eta = rate > 0.0 ? duration(left / rate) : std::string("?");
    std::string line = fmt::format(
        "step {}/{}  t = {:.6g}  {:.4g} steps/s  ETA {}  {} grains  sync {}  gravity {}", stepsDone,
        m_settings.lastStep, m_settings.firstTime + done * m_settings.dt, rate, eta,
        m_settings.grains, m_settings.sync, m_settings.gravity);
    if (m_forceChecks > 0)
        line +=
            fmt::format("  force error {:.2g} (p99 {:.2g})", m_forceError.median, m_forceError.p99);
    if (m_settings.ranks > 1)
        line += fmt::format("  imbalance {:.3g}", m_imbalance);
    return line;
}

void ProgressLine::afterStep(std::int64_t stepsDone) {
    if (!m_settings.enabled)
        return;
    double const t = now();
    bool const last = stepsDone >= m_settings.lastStep;
    if (m_terminal) {
        if (!last && t - m_lastPrint < kTerminalRedrawSeconds)
            return;
        // Carriage return and "erase to end of line": the line is redrawn in place.
        fmt::print("\r{}\x1b[K", text(stepsDone, t - m_start));
        m_drawn = true;
    } else {
        if (m_settings.logSeconds <= 0.0 || t - m_lastPrint < m_settings.logSeconds)
            return;
        fmt::print("{}\n", text(stepsDone, t - m_start));
    }
    std::fflush(stdout);
    m_lastPrint = t;
}

void ProgressLine::clear() {
    if (m_drawn) {
        fmt::print("\r\x1b[K");
        std::fflush(stdout);
        m_drawn = false;
    }
}

void ProgressLine::finish() {
    if (m_drawn) {
        fmt::print("\n");
        std::fflush(stdout);
        m_drawn = false;
    }
}

} // namespace regolith::apps
