// core::openSharedModule: the paths it tries, in order, and the errors it gives when a
// module is missing or is not one of Regolith's.
#include "core/module/SharedModule.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

using regolith::core::openSharedModule;
using regolith::core::SharedModuleSpec;

SharedModuleSpec missing() {
    return {"libregolith_nothing.so",   "REGOLITH_NOTHING_MODULE", "/nonexistent/build/lib.so",
            "/nonexistent/install/lib", "regolith_nothing_module", "this test needs nothing"};
}

/// The file of the C maths library this process uses (whatever the platform calls it).
std::string libmPath() {
    Dl_info info{};
    double (*const cbrtOf)(double) = &::cbrt;
    if (dladdr(reinterpret_cast<void*>(cbrtOf), &info) == 0 || info.dli_fname == nullptr)
        return "";
    return info.dli_fname;
}

std::string errorOf(SharedModuleSpec const& spec) {
    try {
        (void)openSharedModule(spec);
    } catch (regolith::core::Error const& e) {
        return e.what();
    }
    return "";
}

TEST(SharedModule, AMissingModuleNamesEveryPathTriedAndTheVariable) {
    ::setenv("REGOLITH_NOTHING_MODULE", "/nonexistent/from/env.so", 1);
    std::string const what = errorOf(missing());
    ::unsetenv("REGOLITH_NOTHING_MODULE");
    EXPECT_NE(what.find("this test needs nothing, from the module libregolith_nothing.so"),
              std::string::npos)
        << what;
    auto const env = what.find("/nonexistent/from/env.so: no such file");
    auto const besideExe = what.find("/lib/libregolith_nothing.so: no such file");
    auto const installed =
        what.find("/nonexistent/install/lib/libregolith_nothing.so: no such file");
    auto const build = what.find("/nonexistent/build/lib.so: no such file");
    EXPECT_NE(env, std::string::npos) << what;
    EXPECT_NE(besideExe, std::string::npos) << what;
    EXPECT_NE(installed, std::string::npos) << what;
    EXPECT_NE(build, std::string::npos) << what;
    EXPECT_LT(env, besideExe) << "the variable's path is tried first";
    EXPECT_LT(besideExe, installed) << "then ../lib beside the executable";
    EXPECT_LT(installed, build) << "then the install prefix, the build tree last";
    EXPECT_NE(what.find("set REGOLITH_NOTHING_MODULE"), std::string::npos) << what;
}

TEST(SharedModule, ALibraryWithoutTheEntryIsRefusedByName) {
    SharedModuleSpec spec = missing();
    spec.buildPath = libmPath(); // a library, not a Regolith module
    std::string const what = errorOf(spec);
    EXPECT_NE(what.find(spec.buildPath + " has no symbol regolith_nothing_module"),
              std::string::npos)
        << what;
}

TEST(SharedModule, AFileThatIsNoLibraryGivesTheLoadersMessage) {
    // One file per process: the test runs on several ranks in the same directory.
    std::string const text =
        "shared_module_test_not_a_library_" + std::to_string(::getpid()) + ".txt";
    std::ofstream(text) << "not a library\n";
    SharedModuleSpec spec = missing();
    spec.buildPath = text;
    std::string const what = errorOf(spec);
    std::filesystem::remove(text);
    EXPECT_NE(what.find(text + ": "), std::string::npos) << what;
    EXPECT_EQ(what.find(text + ": no such file"), std::string::npos) << what;
}

TEST(SharedModule, FindsTheEntryOfARealLibrary) {
    SharedModuleSpec spec = missing();
    spec.buildPath = libmPath();
    spec.entry = "sqrt";
    auto* root = reinterpret_cast<double (*)(double)>(openSharedModule(spec));
    ASSERT_NE(root, nullptr);
    EXPECT_EQ(root(2.25), 1.5);
}

} // namespace
