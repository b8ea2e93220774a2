#include "core/app/CliOptions.hpp"

#include "core/Error.hpp"
#include "core/config/Suggest.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace regolith::core {

namespace {

/// The CLI11 parser, bound to `o`. One definition for parsing and for the usage text.
std::unique_ptr<CLI::App> makeParser(std::string_view appName, CliOptions& o, std::string& steps) {
    auto app = std::make_unique<CLI::App>(
        "Runs a Regolith scene (TOML). Without a scene file it runs its embedded default "
        "scene.\nScene keys can be overridden with --set section.key=value, where value is "
        "TOML (1e-3, true, \"sos\", [2,2,2]); a bare word is a string (--set sync.method=sos), "
        "and an entry of an array of tables is named as particles[0].radius (or "
        "particles.0.radius).",
        std::string(appName));
    app->set_help_flag("-h,--help", "Print this help and exit");
    app->add_option("scene", o.scenePath, "Scene file (TOML); default: the embedded scene")
        ->type_name("SCENE.toml");
    app->add_option("--set", o.overrides, "Override a scene key (repeatable)")
        ->type_name("SECTION.KEY=VALUE")
        ->allow_extra_args(false);
    app->add_option("--json", o.jsonPath, "Write the run summary (JSON) here, from rank 0")
        ->type_name("FILE");
    app->add_option("--dump", o.dumpPath, "Write the final particles (CSV, sorted by uid) here")
        ->type_name("FILE");
    app->add_option("--steps", steps,
                    "The step to end at (sets time.steps; after --restart a total, not the "
                    "steps left)")
        ->type_name("N");
    app->add_option("--output", o.outputDir, "Output directory (overrides output.dir)")
        ->type_name("DIR");
    app->add_option("--restart", o.restartPath, "Start from this checkpoint")
        ->type_name("CHECKPOINT");
    app->add_flag("--quiet", o.quiet, "Print only warnings and errors");
    app->add_flag("--version", o.version, "Print the version and exit");
    return app;
}

/// "; did you mean '--steps'?" for the first argument that looks like an option the parser does
/// not know but is a plausible misspelling of one it does (closestMatch), else "".
std::string suggestOption(CLI::App const& app, int argc, char const* const* argv) {
    std::vector<std::string> known;
    for (CLI::Option const* option : app.get_options())
        for (std::string const& name : option->get_lnames())
            known.push_back("--" + name);
    for (int k = 1; k < argc; ++k) {
        std::string_view arg = argv[k];
        if (!arg.starts_with("--"))
            continue;
        arg = arg.substr(0, arg.find('='));
        if (std::find(known.begin(), known.end(), arg) != known.end())
            continue;
        if (auto const match = closestMatch(arg, known))
            return fmt::format("; did you mean '{}' for '{}'?", *match, arg);
    }
    return "";
}

/// `s` as a TOML basic string, quotes included.
std::string tomlString(std::string_view s) {
    std::string out = "\"";
    for (char const c : s) {
        if (c == '"' || c == '\\')
            out += '\\';
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
        else
            out += c;
    }
    return out + "\"";
}

/// `--steps` in base 10 (CLI11's own conversion reads "010" as octal and caps an overflow
/// silently); the scene's rules (time.steps >= 0) apply afterwards.
std::int64_t parseSteps(std::string const& text) {
    std::int64_t steps = 0;
    char const* const end = text.data() + text.size();
    auto const [last, error] = std::from_chars(text.data(), end, steps);
    if (text.empty() || error != std::errc{} || last != end)
        throw InputError(fmt::format("--steps {}: expected a decimal integer{}", text,
                                     error == std::errc::result_out_of_range ? " below 2^63" : ""));
    return steps;
}

} // namespace

std::string_view version() {
    return REGOLITH_VERSION;
}

CliOptions parseCommandLine(int argc, char const* const* argv, std::string_view appName) {
    CliOptions options;
    std::string steps;
    auto app = makeParser(appName, options, steps);
    try {
        app->parse(argc, argv);
    } catch (CLI::CallForHelp const&) {
        options.help = true;
        return options;
    } catch (CLI::ParseError const& e) {
        throw InputError(fmt::format("{}{} (run '{} --help' for the options)", e.what(),
                                     suggestOption(*app, argc, argv), appName));
    }
    if (app->count("--steps") > 0)
        options.steps = parseSteps(steps);
    // An empty name was ignored: --restart "" started afresh, --json "" wrote nothing.
    for (char const* name : {"--json", "--dump", "--output", "--restart", "scene"})
        if (app->count(name) > 0 && app->get_option(name)->as<std::string>().empty())
            throw InputError(
                fmt::format("{}: expected a {} name, got an empty string", name,
                            std::string_view(name) == "--output" ? "directory" : "file"));
    return options;
}

std::string usage(std::string_view appName) {
    CliOptions options;
    std::string steps;
    return makeParser(appName, options, steps)->help();
}

void applySceneOptions(CliOptions const& options, ConfigTable& scene) {
    for (auto const& assignment : options.overrides)
        scene.applyOverride(assignment);
    if (options.steps)
        scene.applyOverride(fmt::format("time.steps={}", *options.steps),
                            fmt::format("--steps {}", *options.steps));
    if (!options.outputDir.empty())
        scene.applyOverride("output.dir=" + tomlString(options.outputDir),
                            "--output " + options.outputDir);
}

} // namespace regolith::core
