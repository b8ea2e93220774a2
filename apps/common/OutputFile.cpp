#include "apps/common/OutputFile.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace regolith::apps {

namespace {

/// Runs `action` on rank 0; an InputError there is re-thrown on every rank.
template <class Action>
void onRootForAll(core::Comm const& comm, Action&& action) {
    std::string failure;
    if (comm.rank() == 0) {
        try {
            action();
        } catch (core::InputError const& e) {
            failure = e.what();
            if (failure.empty())
                failure = "unknown failure";
        }
    }
    comm.broadcast(failure, 0);
    if (!failure.empty())
        throw core::InputError(failure);
}

[[noreturn]] void failWrite(std::string const& tmp, std::string const& path, std::string_view why) {
    std::remove(tmp.c_str());
    throw core::InputError(fmt::format("cannot write '{}': {}", path, why));
}

std::string directoryOf(std::string const& path) {
    auto const dir = std::filesystem::path(path).parent_path();
    return dir.empty() ? std::string(".") : dir.string();
}

} // namespace

void writeFileAtomically(std::string const& path, std::string_view text) {
    std::string const tmp = fmt::format("{}.tmp{}", path, static_cast<long>(getpid()));
    auto const fail = [&](std::string_view why) { failWrite(tmp, path, why); };
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f)
        failWrite(tmp, path, std::strerror(errno));
    bool const written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    int const writeErrno = errno;
    if (std::fclose(f) != 0 || !written)
        fail(std::strerror(written ? errno : writeErrno));
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        fail(std::strerror(errno));
}

void writeFileOnRoot(core::Comm const& comm, std::string const& path, std::string_view text) {
    onRootForAll(comm, [&] { writeFileAtomically(path, text); });
}

void checkWritable(core::Comm const& comm, std::string const& path, std::string_view option) {
    onRootForAll(comm, [&] {
        std::string const dir = directoryOf(path);
        std::error_code ec;
        if (std::filesystem::is_directory(path, ec))
            throw core::InputError(fmt::format("{} {}: is a directory", option, path));
        // Created as the VTK and checkpoint output directories are: `--json out/summary.json`
        // in a fresh directory works.
        if (!std::filesystem::is_directory(dir, ec)) {
            std::error_code made;
            std::filesystem::create_directories(dir, made);
            if (!std::filesystem::is_directory(dir, ec))
                throw core::InputError(
                    fmt::format("{} {}: cannot create the directory '{}': {}", option, path, dir,
                                made ? made.message() : (ec ? ec.message() : "not a directory")));
        }
        // A file created and removed there, as the write will (access() says yes to root
        // even where nothing can be created, e.g. in /proc, and the run's end is too late).
        std::string const probe = fmt::format("{}.tmp{}", path, static_cast<long>(getpid()));
        std::FILE* f = std::fopen(probe.c_str(), "wb");
        if (f == nullptr)
            throw core::InputError(fmt::format("{} {}: cannot create a file in '{}': {}", option,
                                               path, dir, std::strerror(errno)));
        std::fclose(f);
        std::remove(probe.c_str());
    });
}

} // namespace regolith::apps
