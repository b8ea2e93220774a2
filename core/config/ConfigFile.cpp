#include "core/config/ConfigFile.hpp"

#include "core/Error.hpp"
#include "core/file/Files.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace regolith::core {

std::string readTextFile(std::string const& path) {
    // A FIFO would block the read, /dev/zero fill the memory: only regular files are read.
    std::string const why = whyNotRegularFile(path);
    if (why == "no such file")
        throw InputError(fmt::format("cannot read '{}': No such file or directory", path));
    if (!why.empty())
        throw InputError(fmt::format("cannot read '{}': it is {}, not a regular file", path, why));
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(fmt::format("cannot read '{}': {}", path, std::strerror(errno)));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
        throw InputError(fmt::format("cannot read '{}': read error", path));
    return text.str();
}

ConfigTable loadConfigFile(Comm const& comm, std::string const& path) {
    // Rank 0 sends "1<text>" or "0<reason>"; every rank then fails or parses alike.
    std::string message;
    if (comm.rank() == 0) {
        try {
            message = readTextFile(path);
            message.insert(message.begin(), '1');
        } catch (InputError const& e) {
            message = '0';
            message += e.what();
        }
    }
    comm.broadcast(message, 0);
    if (message.empty() || message.front() != '1')
        throw InputError(message.empty() ? "cannot read '" + path + "'" : message.substr(1));
    return ConfigTable::fromString(std::string_view(message).substr(1), path);
}

} // namespace regolith::core
