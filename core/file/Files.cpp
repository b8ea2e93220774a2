#include "core/file/Files.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace regolith::core {

std::string whyNotRegularFile(std::string const& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        return errno == ENOENT ? "no such file" : std::strerror(errno);
    if (S_ISREG(st.st_mode))
        return {};
    if (S_ISDIR(st.st_mode))
        return "a directory";
    if (S_ISFIFO(st.st_mode))
        return "a FIFO";
    if (S_ISCHR(st.st_mode))
        return "a character device";
    if (S_ISBLK(st.st_mode))
        return "a block device";
    if (S_ISSOCK(st.st_mode))
        return "a socket";
    return "not a regular file";
}

std::string createTemporaryBeside(std::string const& path, std::string& why) {
    std::string const base = fmt::format("{}.tmp{}", path, static_cast<long>(::getpid()));
    for (int n = 0; n < 1000; ++n) {
        std::string const name = n == 0 ? base : fmt::format("{}.{}", base, n);
        // O_EXCL: fails on any existing entry, a dangling link included, so nothing is
        // followed or truncated; the umask applies as to any new file.
        int const fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return name;
        }
        if (errno != EEXIST) {
            why = std::strerror(errno);
            return {};
        }
    }
    why = fmt::format("every temporary name '{}.<n>' is taken", base);
    return {};
}

void replaceFile(std::string const& path,
                 std::function<void(std::string const& tmp)> const& write) {
    std::string why;
    std::string const tmp = createTemporaryBeside(path, why);
    if (tmp.empty())
        throw InputError(fmt::format("cannot write '{}': {}", path, why));
    try {
        write(tmp);
    } catch (...) {
        std::remove(tmp.c_str());
        throw;
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        why = std::strerror(errno);
        std::remove(tmp.c_str());
        throw InputError(fmt::format("cannot write '{}': {}", path, why));
    }
}

void replaceFileWith(std::string const& path, std::string const& text) {
    replaceFile(path, [&](std::string const& tmp) {
        std::FILE* f = std::fopen(tmp.c_str(), "wb");
        if (f == nullptr)
            throw InputError(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
        bool const written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
        int const writeErrno = errno;
        if (std::fclose(f) != 0 || !written)
            throw InputError(fmt::format("cannot write '{}': {}", path,
                                         std::strerror(written ? errno : writeErrno)));
    });
}

bool sameFile(std::string const& a, std::string const& b) {
    struct stat sa {};
    struct stat sb {};
    bool const hasA = ::stat(a.c_str(), &sa) == 0;
    bool const hasB = ::stat(b.c_str(), &sb) == 0;
    if (hasA && hasB)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    if (hasA != hasB)
        return false;
    std::error_code ec;
    auto const ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ec), ec);
    auto const cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, ec), ec);
    return ca.lexically_normal() == cb.lexically_normal();
}

} // namespace regolith::core
