#include "tests/domain/GlobalForest.hpp"

#include "core/mpi/Buffer.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>

namespace regolith::domain::test {

namespace {

void pack(core::SendBuffer& b, Block const& block) {
    b << block.id.raw() << block.aabb.min << block.aabb.max << block.level << block.owner
      << block.weight << static_cast<std::uint64_t>(block.curveIndex)
      << static_cast<std::uint64_t>(block.neighbours.size());
    for (BlockLink const& l : block.neighbours)
        b << l.id.raw() << l.aabb.min << l.aabb.max << l.owner << l.level << l.shift << l.image;
}

Block unpack(core::RecvBuffer& b) {
    Block block;
    block.id = BlockId::fromRaw(core::read<std::uint64_t>(b));
    b >> block.aabb.min >> block.aabb.max >> block.level >> block.owner >> block.weight;
    block.curveIndex = core::read<std::uint64_t>(b);
    auto const n = core::read<std::uint64_t>(b);
    for (std::uint64_t i = 0; i < n; ++i) {
        BlockLink l;
        l.id = BlockId::fromRaw(core::read<std::uint64_t>(b));
        b >> l.aabb.min >> l.aabb.max >> l.owner >> l.level >> l.shift >> l.image;
        block.neighbours.push_back(l);
    }
    return block;
}

} // namespace

std::ostream& operator<<(std::ostream& os, LinkKey const& k) {
    return os << BlockId::fromRaw(k.id) << "@(" << k.image[0] << "," << k.image[1] << ","
              << k.image[2] << ")";
}

std::vector<GlobalBlock> gatherBlocks(core::Comm const& comm, BlockForest const& forest) {
    core::SendBuffer send;
    send << static_cast<std::uint64_t>(forest.blocks().size());
    for (Block const& b : forest.blocks())
        pack(send, b);
    auto const sizes = comm.allGather(static_cast<int>(send.size()));
    std::vector<int> displs(sizes.size(), 0);
    int total = 0;
    for (std::size_t r = 0; r < sizes.size(); ++r) {
        displs[r] = total;
        total += sizes[r];
    }
    std::vector<std::byte> all(static_cast<std::size_t>(total));
    core::Comm::check(MPI_Allgatherv(send.data(), static_cast<int>(send.size()), MPI_BYTE,
                                     all.data(), sizes.data(), displs.data(), MPI_BYTE, comm.raw()),
                      "MPI_Allgatherv");
    std::vector<GlobalBlock> out;
    for (std::size_t r = 0; r < sizes.size(); ++r) {
        auto const begin = all.begin() + displs[r];
        core::RecvBuffer recv(std::vector<std::byte>(begin, begin + sizes[r]));
        auto const n = core::read<std::uint64_t>(recv);
        for (std::uint64_t i = 0; i < n; ++i)
            out.push_back(GlobalBlock{unpack(recv), static_cast<int>(r)});
    }
    std::sort(out.begin(), out.end(), [](GlobalBlock const& a, GlobalBlock const& b) {
        return a.block.curveIndex < b.block.curveIndex;
    });
    return out;
}

std::vector<PeriodicImage> candidateImages(std::array<bool, 3> const& periodic) {
    std::vector<PeriodicImage> out;
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                PeriodicImage const o{x, y, z};
                bool ok = true;
                for (int a = 0; a < 3; ++a)
                    ok = ok && (periodic[a] || o[a] == 0);
                if (ok)
                    out.push_back(o);
            }
    return out;
}

core::Vec3 translation(core::AABB const& domain, PeriodicImage const& o) {
    core::Vec3 const e = domain.extent();
    return {o[0] * e[0], o[1] * e[1], o[2] * e[2]};
}

bool touchesWithin(core::AABB const& a, core::AABB const& b, core::Vec3 const& tol) {
    for (int i = 0; i < 3; ++i)
        if (a.min[i] > b.max[i] + tol[i] || b.min[i] > a.max[i] + tol[i])
            return false;
    return true;
}

core::Vec3 finestEdge(std::vector<GlobalBlock> const& all) {
    core::Vec3 h = core::Vec3::Constant(std::numeric_limits<double>::max());
    for (GlobalBlock const& g : all)
        h = h.cwiseMin(g.block.aabb.extent());
    return h;
}

std::vector<LinkKey> touchingImages(std::vector<GlobalBlock> const& all, Block const& a,
                                    core::AABB const& domain, std::array<bool, 3> const& periodic) {
    core::Vec3 const tol = 1e-6 * finestEdge(all);
    std::vector<LinkKey> out;
    for (PeriodicImage const& o : candidateImages(periodic)) {
        core::Vec3 const t = translation(domain, o);
        for (GlobalBlock const& g : all) {
            if (g.block.id == a.id && o == PeriodicImage{0, 0, 0})
                continue;
            if (touchesWithin(g.block.aabb.shifted(t), a.aabb, tol))
                out.push_back(LinkKey{g.block.id.raw(), o});
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<LinkKey> keysOf(std::vector<BlockLink const*> const& links) {
    std::vector<LinkKey> out;
    for (BlockLink const* l : links)
        out.push_back(LinkKey{l->id.raw(), l->image});
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<ForestCase> forestCases() {
    using core::Vec3;
    auto spec = [](Vec3 lo, Vec3 hi, std::array<int, 3> n, std::array<bool, 3> p) {
        ForestSpec s;
        s.domain = {lo, hi};
        s.rootBlocks = n;
        s.periodic = p;
        return s;
    };
    std::vector<ForestCase> cases;
    cases.push_back({"plain", spec({0, 0, 0}, {4, 3, 2}, {4, 3, 2}, {false, false, false})});
    cases.push_back({"periodic", spec({-1, -2, 0.5}, {2, 1, 3.5}, {3, 3, 3}, {true, true, true})});
    // Refined at a domain corner with periodic x and y: balance reaches across the boundary.
    ForestSpec corner = spec({0, 0, 0}, {80, 80, 80}, {4, 4, 4}, {true, true, false});
    corner.refine.push_back({{Vec3(0, 0, 0), Vec3(8, 8, 8)}, 2});
    cases.push_back({"refinedCorner", corner});
    // A point refined to level 3 in a fully periodic 2x2x2 grid: the 2:1 ripple wraps around.
    ForestSpec point = spec({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {true, true, true});
    point.refine.push_back({{Vec3(0, 0, 0), Vec3(0, 0, 0)}, 3});
    cases.push_back({"refinedPointPeriodic", point});
    cases.push_back({"single", spec({0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {true, true, true})});
    cases.push_back({"twoAcrossX", spec({0, 0, 0}, {2, 1, 1}, {2, 1, 1}, {true, false, false})});
    // Two root blocks on y, one on x and z, all periodic, refined inside one of them.
    ForestSpec two = spec({0, 0, 0}, {1, 2, 1}, {1, 2, 1}, {true, true, true});
    two.refine.push_back({{Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.2, 0.2)}, 2});
    cases.push_back({"twoPeriodicRefined", two});
    cases.push_back({"longX", spec({0, 0, 0}, {1000, 1, 1}, {100, 1, 1}, {true, false, false})});
    cases.push_back({"flatZ", spec({0, 0, 0}, {1, 1, 1}, {1, 1, 64}, {true, true, true})});
    // Two refine regions of different levels next to coarse blocks, no periodicity.
    ForestSpec mixed = spec({0, 0, 0}, {3, 2, 1}, {3, 2, 1}, {false, false, false});
    mixed.refine.push_back({{Vec3(0.2, 0.2, 0.2), Vec3(0.3, 0.3, 0.3)}, 3});
    mixed.refine.push_back({{Vec3(2.5, 1.5, 0.5), Vec3(2.5, 1.5, 0.5)}, 1});
    cases.push_back({"mixedLevels", mixed});
    return cases;
}

std::vector<ForestCase> forestCasesBothWays() {
    std::vector<ForestCase> cases = forestCases();
    std::size_t const n = cases.size();
    for (std::size_t i = 0; i < n; ++i) {
        ForestCase merged = cases[i];
        merged.name += "Merged";
        merged.subdomains = Subdomains::RankBoxes;
        cases.push_back(merged);
    }
    return cases;
}

double randomWeight(core::AABB const& box, int level) {
    core::Vec3 const c = box.center();
    std::uint64_t z = static_cast<std::uint64_t>(level) * 0x9e3779b97f4a7c15ULL;
    for (int a = 0; a < 3; ++a) {
        z ^= std::bit_cast<std::uint64_t>(c[a]) + 0x9e3779b97f4a7c15ULL + (z << 6) + (z >> 2);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        z ^= z >> 31;
    }
    double const u = static_cast<double>(z >> 11) * 0x1.0p-53;
    return 0.1 + 9.9 * u;
}

} // namespace regolith::domain::test
