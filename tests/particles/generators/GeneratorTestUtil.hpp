#pragma once
// Helpers shared by the generator tests: entry builders, a brute-force overlap oracle with
// the minimum-image convention, bitwise grain comparison and (de)serialisation for gathers.
#include "core/Error.hpp"
#include "particles/generators/GeneratorSpec.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/generators/ParticleGenerator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace regolith::testing {

using particles::AgglomerateSpec;
using particles::GrainInit;
using particles::LatticeKind;
using particles::LatticeSpec;
using particles::ListSpec;
using particles::ParticleSpec;
using Periodic = std::array<bool, 3>;

inline core::AABB box(core::Vec3 const& lo, core::Vec3 const& hi) {
    return {lo, hi};
}

/// The entry of kind `kind` with material type `type`.
inline ParticleSpec withType(ParticleSpec::Kind kind, std::uint32_t type) {
    ParticleSpec spec;
    spec.kind = std::move(kind);
    spec.type = type;
    return spec;
}

inline ParticleSpec lattice(LatticeKind kind, double spacing, double radius,
                            core::AABB const& region,
                            particles::VelocitySpec velocity = core::Vec3(0.0, 0.0, 0.0)) {
    LatticeSpec s;
    s.lattice = kind;
    s.spacing = spacing;
    s.radius = radius;
    s.density = 2.5;
    s.region = region;
    s.velocity = velocity;
    return withType(s, 0);
}

inline ParticleSpec sphereList(std::vector<core::Vec3> positions, std::vector<double> radii) {
    ListSpec s;
    s.position = std::move(positions);
    s.radius = std::move(radii);
    s.density = 3.0;
    return withType(s, 1);
}

inline ParticleSpec agglomerate(core::Vec3 const& centre, double radius, double rMin, double rMax,
                                std::int64_t count, std::uint64_t seed) {
    AgglomerateSpec s;
    s.center = centre;
    s.radius = radius;
    s.grainRadiusMin = rMin;
    s.grainRadiusMax = rMax;
    s.count = count;
    s.velocity = core::Vec3(0.0, 5.0, 0.0);
    s.density = 3000.0;
    s.seed = seed;
    return withType(s, 2);
}

/// Minimum-image separation vector a - b (independent of the generators' image search).
inline core::Vec3 minImage(core::Vec3 const& a, core::Vec3 const& b, core::AABB const& domain,
                           Periodic const& periodic) {
    core::Vec3 d = a - b;
    for (int k = 0; k < 3; ++k)
        if (periodic[static_cast<std::size_t>(k)]) {
            double const length = domain.max[k] - domain.min[k];
            d[k] -= length * std::round(d[k] / length);
        }
    return d;
}

inline bool overlapMinImage(GrainInit const& a, GrainInit const& b, core::AABB const& domain,
                            Periodic const& periodic) {
    double const reach = a.radius + b.radius;
    return minImage(a.position, b.position, domain, periodic).squaredNorm() < reach * reach;
}

/// Every value of the grains equal bit for bit.
inline bool bitwiseEqual(GrainInit const& a, GrainInit const& b) {
    auto same = [](core::Vec3 const& x, core::Vec3 const& y) {
        return std::memcmp(x.data(), y.data(), 3 * sizeof(double)) == 0;
    };
    auto sameD = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    return a.uid == b.uid && same(a.position, b.position) && same(a.velocity, b.velocity) &&
           same(a.angularVelocity, b.angularVelocity) && sameD(a.radius, b.radius) &&
           sameD(a.density, b.density) && sameD(a.mass, b.mass) && a.type == b.type &&
           a.entry == b.entry;
}

/// EXPECTs that the two uid-sorted lists hold the same grains bit for bit.
inline void expectSameGrains(std::vector<GrainInit> const& got, std::vector<GrainInit> const& want,
                             std::string const& what) {
    EXPECT_EQ(got.size(), want.size()) << what;
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < std::min(got.size(), want.size()); ++i)
        if (!bitwiseEqual(got[i], want[i]) && ++mismatches <= 5)
            ADD_FAILURE() << what << ": grain " << i << " differs (uid " << got[i].uid << " vs "
                          << want[i].uid << ")";
    EXPECT_EQ(mismatches, 0u) << what;
}

/// Fixed-size little records for gathering grains across ranks as a string.
inline std::string packGrains(std::vector<GrainInit> const& grains) {
    std::string out;
    for (auto const& g : grains) {
        std::array<double, 13> v{g.position.x(),
                                 g.position.y(),
                                 g.position.z(),
                                 g.velocity.x(),
                                 g.velocity.y(),
                                 g.velocity.z(),
                                 g.angularVelocity.x(),
                                 g.angularVelocity.y(),
                                 g.angularVelocity.z(),
                                 g.radius,
                                 g.density,
                                 g.mass,
                                 0.0};
        std::array<std::uint32_t, 2> t{g.type, g.entry};
        out.append(reinterpret_cast<char const*>(&g.uid), sizeof g.uid);
        out.append(reinterpret_cast<char const*>(v.data()), sizeof v);
        out.append(reinterpret_cast<char const*>(t.data()), sizeof t);
    }
    return out;
}

inline std::vector<GrainInit> unpackGrains(std::string const& s) {
    constexpr std::size_t kRecord =
        sizeof(std::uint64_t) + 13 * sizeof(double) + 2 * sizeof(std::uint32_t);
    std::vector<GrainInit> out;
    for (std::size_t at = 0; at + kRecord <= s.size(); at += kRecord) {
        GrainInit g;
        std::array<double, 13> v{};
        std::array<std::uint32_t, 2> t{};
        std::memcpy(&g.uid, s.data() + at, sizeof g.uid);
        std::memcpy(v.data(), s.data() + at + sizeof g.uid, sizeof v);
        std::memcpy(t.data(), s.data() + at + sizeof g.uid + sizeof v, sizeof t);
        g.position = {v[0], v[1], v[2]};
        g.velocity = {v[3], v[4], v[5]};
        g.angularVelocity = {v[6], v[7], v[8]};
        g.radius = v[9];
        g.density = v[10];
        g.mass = v[11];
        g.type = t[0];
        g.entry = t[1];
        out.push_back(g);
    }
    return out;
}

/// A file name private to this process (every rank runs every test).
inline std::filesystem::path tempPath(std::string const& name) {
    return std::filesystem::temp_directory_path() /
           ("regolith_generators_" + std::to_string(::getpid()) + "_" + name);
}

/// Writes `text` to a private temp file, removed on destruction.
class TempFile {
public:
    TempFile(std::string const& name, std::string const& text)
        : m_path(tempPath(name)) {
        std::ofstream(m_path) << text;
    }
    ~TempFile() {
        std::error_code ec;
        std::filesystem::remove(m_path, ec);
    }
    TempFile(TempFile const&) = delete;
    TempFile& operator=(TempFile const&) = delete;
    [[nodiscard]] std::string path() const { return m_path.string(); }

private:
    std::filesystem::path m_path;
};

/// The message of the core::InputError thrown by `f`, or "" (and a failure) if none.
template <class F>
std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (core::InputError const& e) {
        return e.what();
    } catch (std::exception const& e) {
        ADD_FAILURE() << "expected core::InputError, got another exception: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected core::InputError, nothing was thrown";
    return {};
}

} // namespace regolith::testing
