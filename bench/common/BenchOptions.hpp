#pragma once
/// The command line of the C++ benchmarks: "--key value" pairs among the keys a benchmark
/// knows. `--help` (or -h) lists them; an unknown key, or a key without its value, is named
/// and nothing runs (benchmarks take minutes: a misspelt option must not start the default
/// suite). Every rank parses the same argv, so every rank takes the same way out; rank 0 prints.
#include <cstdio>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace regolith::bench {

struct BenchOptions {
    std::vector<std::pair<std::string, std::string>> pairs; ///< in command-line order
    int exitCode = -1; ///< >= 0: main returns it at once (after --help, or an error)
};

inline BenchOptions parseBenchOptions(int argc, char** argv, std::string_view program,
                                      std::initializer_list<std::string_view> known, bool print) {
    BenchOptions out;
    auto listKnown = [&](std::FILE* to) {
        std::fprintf(to, "usage: %.*s", static_cast<int>(program.size()), program.data());
        for (std::string_view k : known)
            std::fprintf(to, " [%.*s VALUE]", static_cast<int>(k.size()), k.data());
        std::fprintf(to, "\n");
    };
    for (int i = 1; i < argc; i += 2) {
        std::string const key = argv[i];
        if (key == "--help" || key == "-h") {
            if (print)
                listKnown(stdout);
            out.exitCode = 0;
            return out;
        }
        bool isKnown = false;
        for (std::string_view k : known)
            isKnown = isKnown || k == key;
        char const* problem = !isKnown        ? "unknown option"
                              : i + 1 >= argc ? "no value for"
                                              : nullptr;
        if (problem) {
            if (print) {
                std::fprintf(stderr, "%.*s: %s %s\n", static_cast<int>(program.size()),
                             program.data(), problem, key.c_str());
                listKnown(stderr);
            }
            out.exitCode = 2;
            return out;
        }
        out.pairs.emplace_back(key, argv[i + 1]);
    }
    return out;
}

} // namespace regolith::bench
