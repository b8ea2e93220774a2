#include "apps/common/OutputDirLock.hpp"

#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "core/mpi/AgreeOnInputError.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/file.h>
#include <unistd.h>
#include <utility>

namespace regolith::apps {

namespace {

/// Takes the lock of `dir` for this process: the folder, open, or -1 where there is no folder
/// to lock (it cannot be made: the outputs' own checks name what fails) or the file system
/// keeps no locks (warned). Throws core::InputError if another process holds it.
int lockFolder(std::string const& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    int const fd = ec ? -1 : ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    std::string const where = fmt::format("output.dir = \"{}\"", dir);
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0)
        return fd;
    int const why = errno;
    ::close(fd);
    if (why == EWOULDBLOCK)
        throw core::InputError(fmt::format("{}: another run is writing there (it holds the "
                                           "folder's lock); give this run another folder "
                                           "(--output DIR or output.dir)",
                                           where));
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
        ::close(m_fd); // releases the lock
}

} // namespace regolith::apps
