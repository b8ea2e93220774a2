#include "apps/common/OutputFile.hpp"

#include "core/Error.hpp"
#include "core/file/Files.hpp"

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

std::string directoryOf(std::string const& path) {
    auto const dir = std::filesystem::path(path).parent_path();
    return dir.empty() ? std::string(".") : dir.string();
}

/// Writes `text` to `path` opened with `mode`; the reason it failed, or "".
std::string writeAll(std::string const& path, char const* mode, std::string_view text) {
    std::FILE* f = std::fopen(path.c_str(), mode);
    if (!f)
        return std::strerror(errno);
    bool const written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    int const writeErrno = errno;
    if (std::fclose(f) != 0 || !written)
        return std::strerror(written ? errno : writeErrno);
    return {};
}

/// The file a write to `path` replaces: through a symbolic link the file it names (the link
/// stays), else `path`.
std::string replacedFile(std::string const& path) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec)))
        return path;
    auto const resolved = std::filesystem::weakly_canonical(path, ec);
    return ec ? path : resolved.string();
}

} // namespace

bool writtenInPlace(std::string const& path) {
    std::error_code ec;
    // /dev/stdout redirected to a file resolves to that regular file (through /proc/self/fd):
    // replacing it would cut the run's own log; anything under /dev or /proc is written in
    // place.
    auto const st = std::filesystem::status(path, ec);
    std::string const absolute = std::filesystem::absolute(path, ec).lexically_normal().string();
    if (std::filesystem::exists(st) &&
        (absolute.starts_with("/dev/") || absolute.starts_with("/proc/")))
        return true;
    return std::filesystem::exists(st) && !std::filesystem::is_regular_file(st) &&
           !std::filesystem::is_directory(st);
}

void writeFileAtomically(std::string const& path, std::string_view text) {
    // A FIFO's reader, a device, /dev/stdout redirected to a log: written in place, appending.
    if (writtenInPlace(path)) {
        if (std::string const why = writeAll(path, "ab", text); !why.empty())
            throw core::InputError(fmt::format("cannot write '{}': {}", path, why));
        return;
    }
    // Through a fresh temporary beside the file replaced (a leftover one is never reused).
    core::replaceFile(replacedFile(path), [&](std::string const& tmp) {
        if (std::string const why = writeAll(tmp, "wb", text); !why.empty())
            throw core::InputError(fmt::format("cannot write '{}': {}", path, why));
    });
}

void writeFileOnRoot(core::Comm const& comm, std::string const& path, std::string_view text) {
    onRootForAll(comm, [&] { writeFileAtomically(path, text); });
}

void checkWritable(core::Comm const& comm, std::string const& path, std::string_view option) {
    onRootForAll(comm, [&] {
        std::string const dir = directoryOf(replacedFile(path));
        std::error_code ec;
        if (std::filesystem::is_directory(path, ec))
            throw core::InputError(fmt::format("{} {}: is a directory", option, path));
        // "newdir/" names a directory: refused before the directory is made and the run done.
        if (std::filesystem::path(path).filename().empty() || path.ends_with("/.") ||
            path.ends_with("/..") || path == "." || path == "..")
            throw core::InputError(
                fmt::format("{} {}: names a directory, expected a file name", option, path));
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
        // A FIFO or a device is written in place (writeFileAtomically): it must be writable.
        if (writtenInPlace(path)) {
            if (::access(path.c_str(), W_OK) != 0)
                throw core::InputError(
                    fmt::format("{} {}: not writable: {}", option, path, std::strerror(errno)));
            return;
        }
        // A file created and removed there, as the write will (access() says yes to root
        // even where nothing can be created, e.g. in /proc, and the run's end is too late).
        std::string why;
        std::string const probe = core::createTemporaryBeside(replacedFile(path), why);
        if (probe.empty())
            throw core::InputError(
                fmt::format("{} {}: cannot create a file in '{}': {}", option, path, dir, why));
        std::remove(probe.c_str());
    });
}

} // namespace regolith::apps
