#pragma once
// For the tests of Regolith's shared modules (core/module/SharedModule.hpp): is a library
// mapped into this process yet?
#include <fstream>
#include <string>

namespace regolith::test {

/// Is a file whose path contains `name` mapped into this process (/proc/self/maps)?
inline bool isMapped(std::string const& name) {
    std::ifstream maps("/proc/self/maps");
    std::string line;
    while (std::getline(maps, line))
        if (line.find(name) != std::string::npos)
            return true;
    return false;
}

} // namespace regolith::test
