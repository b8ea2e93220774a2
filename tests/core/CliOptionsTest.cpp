// The command line shared by every app: parsing, errors, and how options edit the scene.
#include "core/app/CliOptions.hpp"

#include "tests/core/ConfigTestUtil.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace regolith::core;
using regolith::testing::inputErrorOf;

namespace {

CliOptions parse(std::vector<std::string> const& args) {
    std::vector<std::string> all{"regolith"};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char const*> argv;
    for (auto const& a : all)
        argv.push_back(a.c_str());
    return parseCommandLine(static_cast<int>(argv.size()), argv.data(), "regolith");
}

} // namespace

TEST(CliOptions, EveryOption) {
    auto const o = parse({"--set", "time.dt=1e-3", "gas.toml", "--set=sync.method=sos", "--json",
                          "s.json", "--dump", "f.csv", "--steps", "12", "--output", "out dir",
                          "--restart", "c.h5", "--quiet"});
    EXPECT_EQ(o.scenePath, "gas.toml");
    EXPECT_EQ(o.overrides, (std::vector<std::string>{"time.dt=1e-3", "sync.method=sos"}));
    EXPECT_EQ(o.jsonPath, "s.json");
    EXPECT_EQ(o.dumpPath, "f.csv");
    EXPECT_EQ(o.steps, 12);
    EXPECT_EQ(o.outputDir, "out dir");
    EXPECT_EQ(o.restartPath, "c.h5");
    EXPECT_TRUE(o.quiet);
    EXPECT_FALSE(o.help);

    auto const none = parse({});
    EXPECT_TRUE(none.scenePath.empty());
    EXPECT_FALSE(none.steps.has_value());
    EXPECT_FALSE(none.quiet);
    EXPECT_TRUE(parse({"--help"}).help);
    EXPECT_NE(usage("regolith").find("--set"), std::string::npos);
}

TEST(CliOptions, BadCommandLinesAreInputErrors) {
    auto err = [](std::vector<std::string> const& a) {
        return inputErrorOf([&] { (void)parse(a); });
    };
    EXPECT_NE(err({"--bogus"}).find("--bogus"), std::string::npos);
    EXPECT_NE(err({"--bogus"}).find("run 'regolith --help'"), std::string::npos);
    // A misspelt option is named with the option meant; a word like no option is not.
    EXPECT_NE(err({"a.toml", "--stpes", "1"}).find("; did you mean '--steps' for '--stpes'?"),
              std::string::npos);
    EXPECT_NE(err({"--quite"}).find("did you mean '--quiet'"), std::string::npos);
    EXPECT_NE(err({"--jsno=s.json"}).find("did you mean '--json' for '--jsno'?"),
              std::string::npos);
    EXPECT_EQ(err({"--bogus"}).find("did you mean"), std::string::npos);
    EXPECT_NE(err({"a.toml", "b.toml"}).find("b.toml"), std::string::npos);
    EXPECT_NE(err({"--steps", "many"}).find("--steps"), std::string::npos);
    // Decimal only (CLI11 itself reads 010 as octal 8, 0x10 as 16), and no silent overflow.
    EXPECT_EQ(parse({"--steps", "010"}).steps, 10);
    EXPECT_EQ(err({"--steps", "0x10"}), "--steps 0x10: expected a decimal integer");
    EXPECT_EQ(err({"--steps", "99999999999999999999"}),
              "--steps 99999999999999999999: expected a decimal integer below 2^63");
    EXPECT_NE(err({"--json"}).find("--json"), std::string::npos);
    // An empty name is refused (it was ignored: --restart "" started a fresh run).
    EXPECT_EQ(err({"--restart", ""}), "--restart: expected a file name, got an empty string");
    EXPECT_EQ(err({"--json", ""}), "--json: expected a file name, got an empty string");
    EXPECT_EQ(err({"--dump", ""}), "--dump: expected a file name, got an empty string");
    EXPECT_EQ(err({"--output", ""}), "--output: expected a directory name, got an empty string");
    EXPECT_EQ(err({""}), "scene: expected a file name, got an empty string");
}

TEST(CliOptions, SceneOptionsEditTheSceneWithTheirOwnOrigin) {
    auto scene = ConfigTable::fromString("[time]\ndt = 0.1\nsteps = 10\n", "s.toml");
    applySceneOptions(parse({"--set", "time.dt=0.5", "--steps", "-3", "--set", "time.steps=4",
                             "--output", "a \"q\" dir"}),
                      scene);
    auto const time = scene.table("time");
    EXPECT_EQ(time.get<double>("dt"), 0.5);
    EXPECT_EQ(time.get<int>("steps"), -3); // --steps is applied after every --set
    EXPECT_EQ(time.location("steps"), "--steps -3");
    EXPECT_EQ(scene.table("output").getString("dir"), "a \"q\" dir");
    EXPECT_EQ(scene.table("output").location("dir"), "--output a \"q\" dir");
}
