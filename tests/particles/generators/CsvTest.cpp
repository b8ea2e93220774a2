// Grain CSV files: a good file (every column, comments, blanks, CRLF), the dump format read
// back with its uids, and the errors: unknown column, bad number, field count, missing
// column, density and mass, duplicate uid, grain outside the domain, missing density, no file.
#include "particles/generators/GrainCsv.hpp"
#include "particles/generators/ParticleGenerator.hpp"
#include "tests/particles/generators/GeneratorTestUtil.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <sstream>
#include <sys/stat.h>
#include <vector>

using namespace regolith;
using namespace regolith::testing;
using core::Vec3;

namespace {

particles::CsvGrainTable parse(std::string const& text) {
    std::istringstream in(text);
    return particles::parseGrainCsv(in, "grains.csv", "particles[3].path");
}

std::string parseError(std::string const& text) {
    return inputErrorOf([&] { (void)parse(text); });
}

void expectContains(std::string const& msg, std::vector<std::string> const& parts) {
    for (auto const& p : parts)
        EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

ParticleSpec fileEntry(std::string const& path, std::optional<double> density = std::nullopt) {
    particles::FileSpec f;
    f.path = path;
    f.density = density;
    return withType(f, 6);
}

core::AABB const kDomain = box(Vec3::Zero(), Vec3(10, 10, 10));

} // namespace

TEST(GrainCsv, ReadsAGoodFile) {
    auto const t = parse("# initial state\n"
                         "x, y, z ,radius,vx,vy,vz,wx,wy,wz,density,type\r\n"
                         "\n"
                         "1.5,2.5,3.5,0.25,0.1,-0.2,+0.3,1,2,3,2650,4\r\n"
                         "   # a comment between grains\n"
                         "4,5,6,1e-1,0,0,0,0,0,0,1000.5,0\n");
    ASSERT_EQ(t.grains.size(), 2u);
    EXPECT_TRUE(t.hasDensity);
    EXPECT_FALSE(t.hasMass);
    EXPECT_FALSE(t.hasUid);
    EXPECT_TRUE(t.hasType);
    auto const& g = t.grains[0];
    EXPECT_EQ(g.line, 4);
    EXPECT_EQ(g.position, Vec3(1.5, 2.5, 3.5));
    EXPECT_EQ(g.velocity, Vec3(0.1, -0.2, 0.3));
    EXPECT_EQ(g.angularVelocity, Vec3(1, 2, 3));
    EXPECT_EQ(g.radius, 0.25);
    EXPECT_EQ(g.density, 2650.0);
    EXPECT_EQ(g.type, 4u);
    EXPECT_EQ(t.grains[1].line, 6);
    EXPECT_EQ(t.grains[1].radius, 0.1);
    EXPECT_EQ(t.grains[1].density, 1000.5);
}

TEST(GrainCsv, DumpFormatReadBackKeepsUidsAndMassesExactly) {
    // The --dump header (docs/design.md, "Dump"); mass kept bit for bit, density derived from it.
    TempFile const f("dump.csv", "uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass\n"
                                 "17,1,1,1,0,0,0,0,0,0.5,0.5,0.1234567890123\n"
                                 "4,3,3,3,1,0,0,0,0,0,0.25,0.0311\n"
                                 "9,5,5,5,0,1,0,0,0,0,0.5,0.52\n");
    std::vector<ParticleSpec> const specs{fileEntry(f.path())};
    auto const out = particles::generateGrains(specs, kDomain, {false, false, false});
    EXPECT_EQ(out.entryUidBegin, (std::vector<std::uint64_t>{0, 18}));
    ASSERT_EQ(out.grains.size(), 3u);
    EXPECT_EQ(out.grains[0].uid, 4u);
    EXPECT_EQ(out.grains[1].uid, 9u);
    EXPECT_EQ(out.grains[2].uid, 17u);
    EXPECT_EQ(out.grains[2].mass, 0.1234567890123);
    EXPECT_EQ(out.grains[2].angularVelocity, Vec3(0, 0, 0.5));
    EXPECT_NEAR(out.grains[2].density, 0.1234567890123 / (4.0 / 3.0 * std::numbers::pi * 0.125),
                1e-15);
    EXPECT_EQ(out.grains[0].type, 6u); // no type column: the entry's type
}

TEST(GrainCsv, UnknownColumnNamesFileLineAndColumn) {
    auto const msg = parseError("x,y,z,radius,colour\n1,1,1,0.5,red\n");
    expectContains(msg, {"particles[3].path", "'grains.csv'", "line 1", "column 5",
                         "unknown column 'colour'", "known:"});
    expectContains(parseError("x,y,z,radius,x\n"), {"line 1", "column 5", "duplicate column 'x'"});
    expectContains(parseError("x,y,radius\n"), {"line 1", "missing required column 'z'"});
    expectContains(parseError("x,y,z,radius,density,mass\n"), {"both a density and a mass"});
    expectContains(parseError("# only a comment\n\n"), {"no header line"});
}

TEST(GrainCsv, BadNumberNamesLineAndColumn) {
    std::string const head = "x,y,z,radius\n1,2,3,0.5\n";
    expectContains(parseError(head + "1,2,abc,0.5\n"),
                   {"particles[3].path", "'grains.csv' line 3", "column 3 (z)",
                    "expected a finite number, got 'abc'"});
    expectContains(parseError(head + "# c\n1,2,3,nan\n"), {"line 4", "column 4 (radius)", "'nan'"});
    expectContains(parseError(head + "1,2,3,0.5x\n"), {"line 3", "column 4", "'0.5x'"});
    expectContains(parseError(head + "1,,3,0.5\n"), {"line 3", "column 2 (y)", "got ''"});
    expectContains(parseError(head + "1,2,3\n"),
                   {"line 3", "expected 4 comma-separated fields", "got 3"});
    expectContains(parseError("uid,x,y,z,radius\n-1,1,1,1,0.5\n"),
                   {"line 2", "column 1 (uid)", "non-negative integer", "'-1'"});
    expectContains(parseError("uid,x,y,z,radius\n1.5,1,1,1,0.5\n"), {"column 1 (uid)", "'1.5'"});
}

TEST(GrainCsv, FileEntryErrorsNameTheEntryFileAndLine) {
    {
        TempFile const f("dup.csv",
                         "uid,x,y,z,radius,density\n3,1,1,1,0.5,1\n# x\n3,4,4,4,0.5,1\n");
        std::vector<ParticleSpec> const specs{fileEntry(f.path())};
        expectContains(inputErrorOf([&] {
                           (void)particles::generateGrains(specs, kDomain, {false, false, false});
                       }),
                       {"particles[0].path", "lines 2 and 4", "duplicate uid 3"});
    }
    {
        TempFile const f("outside.csv", "x,y,z,radius\n1,1,1,0.5\n9.8,5,5,0.5\n");
        std::vector<ParticleSpec> const specs{lattice(LatticeKind::SimpleCubic, 1, 0.4, kDomain),
                                              fileEntry(f.path(), 1.0)};
        auto const msg = inputErrorOf([&] {
            (void)particles::generateGrains(specs, kDomain, {false, false, false});
        });
        expectContains(msg, {"particles[1].path", "line 3", "non-periodic axis x"});
        // Periodic x: the same grain is legal.
        EXPECT_NO_THROW((void)particles::generateGrains(specs, kDomain, {true, false, false}));
    }
    {
        TempFile const f("nodensity.csv", "x,y,z,radius\n1,1,1,0.5\n");
        std::vector<ParticleSpec> const specs{fileEntry(f.path())};
        expectContains(inputErrorOf([&] {
                           (void)particles::generateGrains(specs, kDomain, {false, false, false});
                       }),
                       {"particles[0].density", "neither a density nor a mass column"});
    }
    {
        TempFile const f("badmass.csv", "x,y,z,radius,mass\n1,1,1,0.5,0\n");
        std::vector<ParticleSpec> const specs{fileEntry(f.path())};
        expectContains(inputErrorOf([&] {
                           (void)particles::generateGrains(specs, kDomain, {false, false, false});
                       }),
                       {"particles[0].path", "line 2 (mass)", "must be positive"});
    }
    std::vector<ParticleSpec> const missing{fileEntry(tempPath("does-not-exist.csv").string())};
    expectContains(inputErrorOf([&] {
                       (void)particles::generateGrains(missing, kDomain, {false, false, false});
                   }),
                   {"particles[0].path", "cannot open", "does-not-exist.csv"});
    std::vector<ParticleSpec> const directory{
        fileEntry(std::filesystem::temp_directory_path().string())};
    expectContains(inputErrorOf([&] {
                       (void)particles::generateGrains(directory, kDomain, {false, false, false});
                   }),
                   {"particles[0].path", "is a directory, not a regular file"});
}

TEST(GrainCsv, RefusesFifosAndDevices) {
    // Read, a FIFO blocks until a writer comes and /dev/zero never ends.
    std::string const fifo = tempPath("grains-fifo.csv").string();
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::vector<ParticleSpec> const fromFifo{fileEntry(fifo, 1.0)};
    expectContains(inputErrorOf([&] {
                       (void)particles::generateGrains(fromFifo, kDomain, {false, false, false});
                   }),
                   {"particles[0].path", "is a FIFO, not a regular file"});
    std::filesystem::remove(fifo);
    std::vector<ParticleSpec> const fromZero{fileEntry("/dev/zero", 1.0)};
    expectContains(inputErrorOf([&] {
                       (void)particles::generateGrains(fromZero, kDomain, {false, false, false});
                   }),
                   {"particles[0].path", "'/dev/zero' is a character device, not a regular file"});
}

TEST(GrainCsv, MissingFileNamesTheFolderARelativePathIsTakenFrom) {
    ParticleSpec entry = fileEntry("/nowhere/scenes/grains.csv", 1.0);
    std::get<particles::FileSpec>(entry.kind).resolvedFrom = "/nowhere/scenes";
    std::vector<ParticleSpec> const specs{entry};
    expectContains(inputErrorOf([&] {
                       (void)particles::generateGrains(specs, kDomain, {false, false, false});
                   }),
                   {"particles[0].path: cannot open '/nowhere/scenes/grains.csv': no such file (a "
                    "relative path is taken from the scene file's folder '/nowhere/scenes')"});
}

TEST(GrainCsv, QuotesAtMostAShortEscapedPrefixOfTheFile) {
    // Any file may be named: a first line without a column name is not quoted at all ...
    auto const shadow = parseError("root:$y$j9T$SECRET0123456789abcdef:19000:0:99999:7:::\n");
    expectContains(shadow, {"'grains.csv' line 1: not a header of grain columns"});
    EXPECT_EQ(shadow.find("SECRET"), std::string::npos) << shadow;
    EXPECT_EQ(shadow.find("root"), std::string::npos) << shadow;
    // ... and a field at most by its first 24 bytes, control bytes escaped (a NUL would end
    // the printed message).
    std::string binary = "x,y,z,radius,ab";
    binary += '\0';
    binary += "cd" + std::string(100, 'q') + "\n";
    auto const column = parseError(binary);
    expectContains(column, {"unknown column 'ab\\x00cdqqqqqqqqqqqqqqqqqqq...'"});
    EXPECT_EQ(column.find('\0'), std::string::npos);
    auto const number = parseError("x,y,z,radius\n1,2," + std::string(80, '7') + "e,0.5\n");
    expectContains(number, {"got '777777777777777777777777...'"});
}

TEST(GrainCsv, RowIndexUidsAndDensityFromTheEntry) {
    TempFile const f("plain.csv", "x,y,z,radius,vz\n1,1,1,0.5,-2\n3,3,3,0.5,0\n5,5,5,0.25,0\n");
    std::vector<ParticleSpec> const specs{sphereList({Vec3(8, 8, 8)}, {1.0}),
                                          fileEntry(f.path(), 2.0)};
    auto const out = particles::generateGrains(specs, kDomain, {false, false, false});
    ASSERT_EQ(out.grains.size(), 4u);
    EXPECT_EQ(out.entryUidBegin, (std::vector<std::uint64_t>{0, 1, 4}));
    EXPECT_EQ(out.grains[1].uid, 1u);
    EXPECT_EQ(out.grains[1].velocity, Vec3(0, 0, -2));
    EXPECT_EQ(out.grains[3].uid, 3u);
    EXPECT_EQ(out.grains[3].density, 2.0);
    EXPECT_EQ(out.grains[3].mass, particles::sphereMass(0.25, 2.0));
}
