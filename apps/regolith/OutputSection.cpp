// The scene's [output] section: where the run writes and how often (docs/guide/scene.md).
#include "apps/regolith/SceneSections.hpp"
#include "core/config/ValueChecks.hpp"

#include <array>
#include <cmath>
#include <string_view>

namespace regolith::apps {

namespace {

using namespace std::string_view_literals;

/// In the order of DumpFormat.
constexpr std::array kDumpFormatNames{"csv"sv, "hdf5"sv};

} // namespace

OutputSection parseOutput(core::ConfigTable const& t) {
    OutputSection s;
    s.dir = t.getOrIf<std::string>(
        "dir", s.dir, [](std::string const& d) { return !d.empty(); }, "a non-empty string");
    s.vtkEvery =
        t.getOrIf<std::int64_t>("vtk_every", 0, core::isNonNegative, "a non-negative integer");
    s.checkpointEvery = t.getOrIf<std::int64_t>("checkpoint_every", 0, core::isNonNegative,
                                                "a non-negative integer");
    s.checkpointKeep = t.getOrIf<std::int64_t>("checkpoint_keep", s.checkpointKeep,
                                               core::isNonNegative, "a non-negative integer");
    s.vtkShadows = t.getOr<bool>("vtk_shadows", false);
    s.progressSeconds = t.getOrIf<double>(
        "progress_seconds", s.progressSeconds,
        [](double v) { return std::isfinite(v) && v >= 0.0; }, "a non-negative number");
    s.thermoEvery =
        t.getOrIf<std::int64_t>("thermo_every", 0, core::isNonNegative, "a non-negative integer");
    s.dumpEvery =
        t.getOrIf<std::int64_t>("dump_every", 0, core::isNonNegative, "a non-negative integer");
    s.dumpFormat = static_cast<DumpFormat>(t.getChoiceOr("dump_format", kDumpFormatNames, 0));
    return s;
}

} // namespace regolith::apps
