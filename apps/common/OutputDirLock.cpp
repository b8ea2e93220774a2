#include "apps/common/OutputDirLock.hpp"

#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "core/mpi/AgreeOnInputError.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>
#include <utility>

namespace regolith::apps {

namespace {

/// A write lock on the whole of `fd`'s file.
struct flock wholeFile() {
    struct flock lock {};
    lock.l_type = F_WRLCK;
    lock.l_whence = SEEK_SET;
    lock.l_start = 0;
    lock.l_len = 0;
    return lock;
}

/// Takes the lock of `dir` for this process: the open lock file, or -1 where the file system
/// keeps no locks (warned). Throws core::InputError if another process holds it.
int lockFolder(std::string const& dir) {
    std::string const where = fmt::format("output.dir = \"{}\"", dir);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
        throw core::InputError(
            fmt::format("{}: cannot create the folder: {}", where, ec.message()));
    std::string const path = (std::filesystem::path(dir) / OutputDirLock::kFileName).string();
    int const fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        throw core::InputError(
            fmt::format("{}: cannot open '{}': {}", where, path, std::strerror(errno)));
    struct flock lock = wholeFile();
    if (::fcntl(fd, F_SETLK, &lock) == 0)
        return fd;
    int const why = errno;
    if (why == EACCES || why == EAGAIN) {
        struct flock holder = wholeFile();
        std::string const who = ::fcntl(fd, F_GETLK, &holder) == 0 && holder.l_type != F_UNLCK
                                    ? fmt::format(" (process {})", holder.l_pid)
                                    : std::string();
        ::close(fd);
        throw core::InputError(fmt::format(
            "{}: another run{} is writing there (it holds '{}'); give this run another folder "
            "(--output DIR or output.dir)",
            where, who, path));
    }
    ::close(fd);
    core::log::warn("{}: the file system keeps no locks ({}): nothing keeps another run from "
                    "writing into the same folder",
                    where, std::strerror(why));
    return -1;
}

} // namespace

OutputDirLock::OutputDirLock(core::Comm const& comm, std::string const& dir) {
    core::agreeOnInputError(comm, [&] {
        if (comm.rank() == 0)
            m_fd = lockFolder(dir);
    });
}

OutputDirLock::OutputDirLock(OutputDirLock&& other) noexcept
    : m_fd(std::exchange(other.m_fd, -1)) {}

OutputDirLock& OutputDirLock::operator=(OutputDirLock&& other) noexcept {
    if (this != &other) {
        if (m_fd >= 0)
            ::close(m_fd);
        m_fd = std::exchange(other.m_fd, -1);
    }
    return *this;
}

OutputDirLock::~OutputDirLock() {
    if (m_fd >= 0)
        ::close(m_fd); // releases the lock; the file stays (removing it would race a waiter)
}

} // namespace regolith::apps
