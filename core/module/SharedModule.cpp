#include "core/module/SharedModule.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

namespace regolith::core {

namespace {

std::vector<std::string> candidates(SharedModuleSpec const& spec) {
    std::vector<std::string> out;
    auto const add = [&](std::string path) {
        if (!path.empty() && std::find(out.begin(), out.end(), path) == out.end())
            out.push_back(std::move(path));
    };
    if (char const* env = std::getenv(spec.envVariable.c_str()); env && env[0] != '\0')
        add(env);
    std::error_code error;
    std::filesystem::path const exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error)
        add((exe.parent_path().parent_path() / "lib" / spec.file).lexically_normal().string());
    if (!spec.installDir.empty())
        add((std::filesystem::path(spec.installDir) / spec.file).string());
    add(spec.buildPath);
    return out;
}

} // namespace

void* openSharedModule(SharedModuleSpec const& spec) {
    std::string tried;
    for (std::string const& path : candidates(spec)) {
        if (!std::filesystem::exists(path)) {
            tried += "\n  " + path + ": no such file";
            continue;
        }
        // RTLD_GLOBAL: the wrapped library's own plug-ins resolve against what it brought.
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
        if (handle == nullptr) {
            char const* e = dlerror();
            tried += "\n  " + path + ": " + (e ? e : "dlopen failed");
            continue;
        }
        void* entry = dlsym(handle, spec.entry.c_str());
        if (entry == nullptr)
            throw Error(path + " has no symbol " + spec.entry);
        return entry;
    }
    throw Error(spec.neededFor + ", from the module " + spec.file + "; tried:" + tried + "\n(set " +
                spec.envVariable + " to its path)");
}

} // namespace regolith::core
