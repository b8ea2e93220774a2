// ConfigTable: typed getters, messages with file:line and key path, unknown-key detection with
// did-you-mean, loading from files (locally and collectively).
#include "core/config/ConfigFile.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/config/Suggest.hpp"
#include "core/mpi/Comm.hpp"
#include "tests/core/ConfigTestUtil.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

using namespace regolith::core;
using regolith::testing::inputErrorOf;

namespace {

// Line numbers matter: the tests below quote them.
constexpr char const* kScene = R"(name = "unit"
[domain]
min = [0, 0, 0]
max = [80, 40.5, 20]
blocks = [4, 2, 1]
periodic = [true, false, true]
[time]
dt = 1
steps = 1000
big = 5000000000
[[particles]]
kind = "list"
radius = [1.5, 2]
position = [[1, 2, 3], [4, 5, 6]]
region = { min = [0, 0, 0], max = [1, 1, 1] }
[[particles]]
kind = "lattice"
)";

ConfigTable scene() {
    return ConfigTable::fromString(kScene, "scene.toml");
}

} // namespace

TEST(ConfigTable, TypedGetters) {
    auto const root = scene();
    EXPECT_EQ(root.getString("name"), "unit");
    auto const domain = root.table("domain");
    EXPECT_EQ(domain.path(), "domain");
    EXPECT_EQ(domain.keyPath("blocks"), "domain.blocks");
    EXPECT_EQ(domain.getVec3("max"), Vec3(80, 40.5, 20));
    EXPECT_EQ((domain.getArray<int, 3>("blocks")), (std::array<int, 3>{4, 2, 1}));
    EXPECT_EQ((domain.get<std::array<bool, 3>>("periodic")),
              (std::array<bool, 3>{true, false, true}));
    EXPECT_EQ(domain.getVector<double>("min"), (std::vector<double>{0, 0, 0}));
    auto const time = root.table("time");
    EXPECT_EQ(time.get<double>("dt"), 1.0); // an integer is a number
    EXPECT_EQ(time.get<int>("steps"), 1000);
    EXPECT_EQ(time.get<std::int64_t>("big"), 5000000000);
    EXPECT_EQ(time.getOr<double>("end", 2.5), 2.5);
    EXPECT_EQ(time.getOr<std::string>("integrator", "verlet"), "verlet");
    EXPECT_EQ(time.kindOf("dt"), ConfigKind::Integer);
    EXPECT_EQ(time.kindOf("nothing"), ConfigKind::Missing);
    EXPECT_FALSE(root.findTable("gravity").has_value());
    EXPECT_TRUE(root.tableArray("walls").empty());

    auto const particles = root.tableArray("particles");
    ASSERT_EQ(particles.size(), 2u);
    EXPECT_EQ(particles[0].path(), "particles[0]");
    EXPECT_EQ(particles[0].getVector<double>("radius"), (std::vector<double>{1.5, 2.0}));
    auto const positions = particles[0].getVector<Vec3>("position");
    ASSERT_EQ(positions.size(), 2u);
    EXPECT_EQ(positions[1], Vec3(4, 5, 6));
    auto const region = particles[0].table("region");
    EXPECT_EQ(region.path(), "particles[0].region");
    EXPECT_EQ(region.getVec3("max"), Vec3(1, 1, 1));
    EXPECT_EQ(particles[1].getString("kind"), "lattice");
    EXPECT_EQ(particles[1].location(), "scene.toml:16");
    EXPECT_EQ(root.location("domain"), "scene.toml:2");
    EXPECT_EQ(domain.location("max"), "scene.toml:4");
    EXPECT_EQ(domain.describe("max"), "[80, 40.5, 20]");
    EXPECT_EQ(particles[0].describe("region"), "{ max = [1, 1, 1], min = [0, 0, 0] }");
}

TEST(ConfigTable, WrongTypesNameFileLineKeyAndValue) {
    auto const root = scene();
    auto const domain = root.table("domain");
    auto const time = root.table("time");
    auto const p0 = root.tableArray("particles")[0];
    EXPECT_EQ(inputErrorOf([&] { (void)root.get<double>("name"); }),
              "scene.toml:1: name: expected a number, got \"unit\" (a string)");
    EXPECT_EQ(inputErrorOf([&] { (void)time.get<bool>("dt"); }),
              "scene.toml:8: time.dt: expected a boolean, got 1 (an integer)");
    EXPECT_EQ(inputErrorOf([&] { (void)time.get<int>("big"); }),
              "scene.toml:10: time.big: expected an integer (32 bit), got 5000000000 (an integer)");
    EXPECT_EQ(inputErrorOf([&] { (void)domain.getArray<int, 2>("blocks"); }),
              "scene.toml:5: domain.blocks: expected an array of 2 integers, got [4, 2, 1]");
    EXPECT_EQ(inputErrorOf([&] { (void)domain.getVec3("periodic"); }),
              "scene.toml:6: domain.periodic: expected an array of 3 numbers, got [true, false, "
              "true]");
    EXPECT_EQ(inputErrorOf([&] { (void)p0.getVector<int>("radius"); }),
              "scene.toml:13: particles[0].radius: expected an array of integers, got [1.5, 2]");
    EXPECT_EQ(inputErrorOf([&] { (void)p0.table("kind"); }),
              "scene.toml:12: particles[0].kind: expected a table, got \"list\" (a string)");
    EXPECT_EQ(inputErrorOf([&] { (void)root.tableArray("domain"); }),
              "scene.toml:2: domain: expected an array of tables ([[domain]] sections), got { "
              "blocks = [4, 2, 1], max = [80, 40.5, 20], min = [0, 0, 0], ... }"); // shortened
    EXPECT_EQ(inputErrorOf([&] {
                  (void)domain.getIf<std::array<int, 3>>(
                      "blocks", [](auto const& b) { return b[2] > 1; },
                      "an array of 3 positive integers");
              }),
              "scene.toml:5: domain.blocks: expected an array of 3 positive integers, got [4, 2, "
              "1]");
    EXPECT_EQ(inputErrorOf([&] { domain.fail("min", "is wrong"); }),
              "scene.toml:3: domain.min: is wrong");
}

TEST(ConfigTable, ChoicesListAlternativesAndSuggestOne) {
    using namespace std::string_view_literals;
    constexpr std::array kMethods{"nns"sv, "sos"sv, "hybrid"sv};
    auto const root =
        ConfigTable::fromString("[sync]\nmethod = \"hybrid\"\nbad = \"sso\"\nnum = 3\n", "c.toml");
    auto const sync = root.table("sync");
    EXPECT_EQ(sync.getChoice("method", kMethods), 2u);
    EXPECT_EQ(sync.getChoiceOr("absent", kMethods, 1), 1u);
    EXPECT_EQ(inputErrorOf([&] { (void)sync.getChoice("bad", kMethods); }),
              "c.toml:3: sync.bad: expected one of \"nns\", \"sos\", \"hybrid\", got \"sso\" "
              "\u2014 did you mean \"sos\"?");
    EXPECT_EQ(inputErrorOf([&] { (void)sync.getChoice("num", kMethods); }),
              "c.toml:4: sync.num: expected a string, got 3 (an integer)");
}

TEST(ConfigTable, MissingKeysAndTables) {
    auto const root = ConfigTable::fromString("[time]\ndtt = 0.1\nsteps = 3\n", "s.toml");
    auto const time = root.table("time");
    EXPECT_EQ(inputErrorOf([&] { (void)time.get<double>("dt"); }),
              "s.toml:1: time.dt: required key is missing (is 'dtt' at s.toml:2 a misspelling "
              "of it?)");
    EXPECT_EQ(inputErrorOf([&] { (void)time.get<double>("end"); }),
              "s.toml:1: time.end: required key is missing");
    EXPECT_EQ(inputErrorOf([&] { (void)root.table("domain"); }),
              "s.toml: missing required table [domain]");
}

TEST(ConfigTable, UnknownKeysAreReportedWithSuggestionsInFileOrder) {
    auto const root = ConfigTable::fromString(R"([domain]
min = [0, 0, 0]
max = [1, 1, 1]
blokcs = [2, 2, 2]
[domian]
x = 1
[[particles]]
kind = "lattice"
spacing = 1.0
[[particles]]
kind = "list"
spacing = 1.0
colour = "red"
)",
                                              "scene.toml");
    auto const domain = root.table("domain");
    (void)domain.getVec3("min");
    (void)domain.getVec3("max");
    (void)domain.getOr<std::array<int, 3>>("blocks", {1, 1, 1});
    auto const particles = root.tableArray("particles");
    (void)particles[0].getString("kind");
    (void)particles[0].get<double>("spacing");
    (void)particles[1].getString("kind");
    EXPECT_EQ(inputErrorOf([&] { root.rejectUnknownKeys(); }),
              "scene.toml:4: unknown key 'domain.blokcs' \u2014 did you mean 'blocks'?\n"
              "scene.toml:5: unknown key 'domian' \u2014 did you mean 'domain'?\n"
              "scene.toml:12: unknown key 'particles[1].spacing' (known keys here: kind)\n"
              "scene.toml:13: unknown key 'particles[1].colour' (known keys here: kind)");
    // A table that was opened but has no unknown keys passes on its own.
    EXPECT_NO_THROW(particles[0].rejectUnknownKeys());
}

TEST(ConfigTable, KeysOfUnopenedTablesAreUnknownButHasMarksKnown) {
    auto const root = ConfigTable::fromString("[a]\nx = 1\n[b]\ny = 2\n", "t.toml");
    EXPECT_TRUE(root.has("a"));
    EXPECT_EQ(inputErrorOf([&] { root.rejectUnknownKeys(); }),
              "t.toml:2: unknown key 'a.x'\nt.toml:3: unknown key 'b' (known keys here: a)");
    (void)root.findTable("b");
    (void)root.table("a").has("x");
    EXPECT_EQ(inputErrorOf([&] { root.rejectUnknownKeys(); }), "t.toml:4: unknown key 'b.y'");
}

TEST(ConfigTable, MalformedTomlNamesLineAndColumn) {
    auto const msg =
        inputErrorOf([] { (void)ConfigTable::fromString("[domain]\nmin = [0, 0\n", "bad.toml"); });
    EXPECT_EQ(msg.rfind("bad.toml:2:", 0), 0u) << msg;
    EXPECT_NE(msg.find("malformed TOML"), std::string::npos) << msg;
    auto const dup =
        inputErrorOf([] { (void)ConfigTable::fromString("a = 1\na = 2\n", "d.toml"); });
    EXPECT_EQ(dup.rfind("d.toml:2:", 0), 0u) << dup;
}

TEST(ConfigFile, MissingFileAndDirectory) {
    EXPECT_EQ(inputErrorOf([] { (void)ConfigTable::fromFile("/nonexistent/scene.toml"); }),
              "cannot read '/nonexistent/scene.toml': No such file or directory");
    EXPECT_EQ(inputErrorOf([] { (void)ConfigTable::fromFile("/tmp"); }),
              "cannot read '/tmp': it is a directory, not a regular file");
}

TEST(ConfigFile, RefusesFifosAndDevices) {
    // Read, a FIFO waits for a writer forever and /dev/zero fills the memory.
    auto const fifo = (std::filesystem::temp_directory_path() /
                       ("regolith-config-fifo-" + std::to_string(getpid())))
                          .string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(inputErrorOf([&] { (void)ConfigTable::fromFile(fifo); }),
              "cannot read '" + fifo + "': it is a FIFO, not a regular file");
    std::filesystem::remove(fifo);
    EXPECT_EQ(inputErrorOf([] { (void)ConfigTable::fromFile("/dev/zero"); }),
              "cannot read '/dev/zero': it is a character device, not a regular file");
}

TEST(ConfigFile, CollectiveLoadGivesEveryRankTheSameTableOrTheSameError) {
    Comm world;
    // One file per job: rank 0's pid names it.
    long pid = static_cast<long>(getpid());
    pid = world.allReduce(world.rank() == 0 ? pid : 0L, ReduceOp::Sum);
    auto const path = (std::filesystem::temp_directory_path() /
                       ("regolith-config-test-" + std::to_string(pid) + ".toml"))
                          .string();
    if (world.rank() == 0)
        std::ofstream(path) << "[time]\ndt = 0.25\n";
    world.barrier();
    std::string message = inputErrorOf([&] {
        auto const root = loadConfigFile(world, path);
        EXPECT_EQ(root.table("time").get<double>("dt"), 0.25);
        EXPECT_EQ(root.sourceName(), path);
    });
    EXPECT_EQ(message, "(no InputError thrown)");
    world.barrier();
    if (world.rank() == 0)
        std::filesystem::remove(path);
    message = inputErrorOf([&] { (void)loadConfigFile(world, path + ".missing"); });
    EXPECT_EQ(message, "cannot read '" + path + ".missing': No such file or directory");
}

TEST(Suggest, EditDistanceAndClosestMatch) {
    EXPECT_EQ(editDistance("", ""), 0u);
    EXPECT_EQ(editDistance("abc", ""), 3u);
    EXPECT_EQ(editDistance("blokcs", "blocks"), 1u); // transposition
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(editDistance("ca", "abc"), 3u); // optimal string alignment, not full Damerau
    std::vector<std::string> const keys{"min", "max", "blocks", "periodic", "refine"};
    EXPECT_EQ(closestMatch("blokcs", keys), "blocks");
    EXPECT_EQ(closestMatch("perodic", keys), "periodic");
    EXPECT_EQ(closestMatch("MAX", keys), "max");
    EXPECT_EQ(closestMatch("mix", keys), "min"); // distance 1 to min and max: first wins
    EXPECT_FALSE(closestMatch("b", std::vector<std::string>{"a"}).has_value()); // no shared letter
    EXPECT_FALSE(closestMatch("colour", keys).has_value());
    EXPECT_FALSE(closestMatch("x", std::vector<std::string>{}).has_value());
}
