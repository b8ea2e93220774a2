// checkSyncInvariants: gather a compact record of every copy and every block box on rank 0
// (InvariantRecords.hpp), check there (one uid at a time, in uid order, so the report is
// deterministic), broadcast.
#include "particles/sync/SyncInvariants.hpp"

#include "core/Error.hpp"
#include "core/mpi/Buffer.hpp"
#include "domain/BlockId.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/sync/InvariantRecords.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>
#include <span>
#include <tuple>
#include <type_traits>
#include <unordered_map>

namespace regolith::particles {

using namespace sync_detail;

namespace {

/// Relative band around the overlap threshold in which either answer is accepted (see header).
constexpr double kThresholdTolerance = 1e-12;

std::string vec(core::Vec3 const& v) {
    return fmt::format("({:.17g}, {:.17g}, {:.17g})", v[0], v[1], v[2]);
}
std::string img(CopyImage const& k) {
    return fmt::format("({},{},{})", k[0], k[1], k[2]);
}
std::string blk(std::uint64_t block, int rank) {
    return fmt::format("block {} (rank {})", domain::BlockId::fromRaw(block).toString(), rank);
}
std::string where(CopyRef const& c) {
    return blk(c.block, c.rank) + " image " + img(c.image);
}

template <class T>
bool sameBits(T const& a, T const& b) {
    static_assert(std::is_trivially_copyable_v<T>);
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}
bool sameBits(core::Vec3 const& a, core::Vec3 const& b) {
    return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}
bool sameBits(core::Quat const& a, core::Quat const& b) {
    return std::memcmp(a.coeffs().data(), b.coeffs().data(), 4 * sizeof(double)) == 0;
}

/// Rank 0's check of the gathered state.
class Checker {
public:
    Checker(domain::ForestGeometry const& geometry, core::Vec3 const& period,
            std::array<bool, 3> const& wrapped, bool converged, double skin)
        : m_geometry(geometry)
        , m_period(period)
        , m_wrapped(wrapped)
        , m_converged(converged)
        , m_skin(skin) {}

    void addBlocks(std::vector<std::pair<std::uint64_t, BlockRecord>> const& blocks) {
        for (auto const& [id, b] : blocks) {
            auto const [at, fresh] = m_blocks.emplace(id, b);
            if (!fresh)
                report(blk(id, b.rank) + " is also held by rank " +
                       std::to_string(at->second.rank));
            m_byRoot[domain::BlockId::fromRaw(id).rootIndex()].push_back(id);
        }
        for (auto& [root, ids] : m_byRoot)
            std::sort(ids.begin(), ids.end());
    }

    void run(std::vector<CopyRecord>& copies) {
        std::sort(copies.begin(), copies.end(), [](CopyRecord const& a, CopyRecord const& b) {
            return std::tuple(a.uid, a.flags.isShadow(), a.rank, a.block, a.image) <
                   std::tuple(b.uid, b.flags.isShadow(), b.rank, b.block, b.image);
        });
        for (std::size_t lo = 0; lo < copies.size();) {
            std::size_t hi = lo;
            while (hi < copies.size() && copies[hi].uid == copies[lo].uid)
                ++hi;
            checkUid(std::span<CopyRecord const>(copies).subspan(lo, hi - lo));
            lo = hi;
        }
    }

    [[nodiscard]] std::vector<std::string> result() {
        if (m_total > m_listed.size())
            m_listed.push_back(
                fmt::format("... and {} more violations", m_total - m_listed.size()));
        return std::move(m_listed);
    }

private:
    void report(std::string s) {
        ++m_total;
        if (m_listed.size() < kMaxListedViolations)
            m_listed.push_back(std::move(s));
    }

    BlockRecord const* findBlock(std::uint64_t id) const {
        auto const it = m_blocks.find(id);
        return it == m_blocks.end() ? nullptr : &it->second;
    }

    void checkUid(std::span<CopyRecord const> group) {
        std::string const u = "uid " + std::to_string(group.front().uid) + ": ";
        for (CopyRecord const& c : group) {
            BlockRecord const* b = findBlock(c.block);
            if (b == nullptr)
                report(u + "copy in " + blk(c.block, c.rank) + ", a block the forest lacks");
            else if (b->rank != c.rank)
                report(u + "copy in " + blk(c.block, c.rank) + ", a block of rank " +
                       std::to_string(b->rank));
        }
        auto const nMasters = static_cast<std::size_t>(std::count_if(
            group.begin(), group.end(), [](CopyRecord const& c) { return c.flags.isMaster(); }));
        if (nMasters == 0) { // sorted masters first
            report(u + "no master, but a shadow in " + where(group.front().where()));
            return;
        }
        CopyRecord const& m = group.front();
        for (std::size_t k = 1; k < nMasters; ++k)
            report(u + "a second master in " + blk(group[k].block, group[k].rank) +
                   " besides the one in " + blk(m.block, m.rank));
        checkMaster(u, m);
        std::span<CopyRecord const> const shadows = group.subspan(nMasters);
        for (CopyRecord const& s : shadows)
            checkShadow(u, m, s);
        checkHolders(u, m, shadows);
        if (!m_converged && m.flags.has(Flag::Spreads))
            return;
        if (!std::isfinite(m.radius) || !m.position.allFinite())
            return report(u + "non-finite position or radius");
        checkPresence(u, m, group);
    }

    void checkMaster(std::string const& u, CopyRecord const& m) {
        BlockRecord const* b = findBlock(m.block);
        if (b != nullptr && !b->box.contains(m.position))
            report(u + "master at " + vec(m.position) + " lies outside its " +
                   blk(m.block, m.rank) + " [" + vec(b->box.min) + ", " + vec(b->box.max) + ")");
        if (!isZero(m.image))
            report(u + "master in " + blk(m.block, m.rank) + " has image " + img(m.image));
        if (m.owner != BlockRef{m.rank, m.block})
            report(u + "master in " + blk(m.block, m.rank) + " names owner " +
                   blk(m.owner.block, m.owner.rank));
    }

    void checkShadow(std::string const& u, CopyRecord const& m, CopyRecord const& s) {
        std::string differs;
        auto field = [&differs](bool same, char const* name) {
            if (!same)
                differs += differs.empty() ? name : std::string(", ") + name;
        };
        field(sameBits(s.position, m.position), "position");
        field(sameBits(s.velocity, m.velocity), "velocity");
        field(sameBits(s.angularVelocity, m.angularVelocity), "angular velocity");
        field(sameBits(s.orientation, m.orientation), "orientation");
        field(sameBits(s.radius, m.radius), "radius");
        field(sameBits(s.mass, m.mass), "mass");
        field(Flags(s.flags).set(Flag::Shadow, false) == Flags(m.flags).set(Flag::Shadow, false),
              "flags");
        if (!differs.empty())
            report(u + "shadow in " + where(s.where()) + " differs from its master in " + differs +
                   " (shadow at " + vec(s.position) + ", master at " + vec(m.position) + ")");
        if (s.owner != BlockRef{m.rank, m.block})
            report(u + "shadow in " + where(s.where()) + " names owner " +
                   blk(s.owner.block, s.owner.rank) + ", but the master is in " +
                   blk(m.block, m.rank));
    }

    void checkHolders(std::string const& u, CopyRecord const& m,
                      std::span<CopyRecord const> shadows) {
        std::vector<CopyRef> const& listed = m.holders;
        if (!std::is_sorted(listed.begin(), listed.end()) ||
            std::adjacent_find(listed.begin(), listed.end()) != listed.end())
            report(u + "the master's shadowHolders are not sorted and unique");
        std::vector<CopyRef> actual;
        for (CopyRecord const& s : shadows)
            actual.push_back(s.where());
        std::sort(actual.begin(), actual.end());
        std::vector<CopyRef> sortedListed = listed;
        std::sort(sortedListed.begin(), sortedListed.end());
        std::vector<CopyRef> diff;
        std::set_difference(actual.begin(), actual.end(), sortedListed.begin(), sortedListed.end(),
                            std::back_inserter(diff));
        for (CopyRef const& c : diff)
            report(u + "shadow in " + where(c) + " is missing from the master's shadowHolders");
        diff.clear();
        std::set_difference(sortedListed.begin(), sortedListed.end(), actual.begin(), actual.end(),
                            std::back_inserter(diff));
        for (CopyRef const& c : diff)
            report(u + "the master's shadowHolders list " + where(c) + ", which holds no shadow");
    }

    /// Check 5: copies exactly where copyNeeded() (within the tolerance band).
    void checkPresence(std::string const& u, CopyRecord const& m,
                       std::span<CopyRecord const> group) {
        double const rIn = m.radius * (1.0 - kThresholdTolerance);
        // With a sync skin a copy may stay while the ball is within r + 2 skin of the block.
        double const rOut = (m.radius + 2.0 * m_skin) * (1.0 + kThresholdTolerance);
        std::string const grain =
            "the grain at " + vec(m.position) + " with radius " + fmt::format("{:.17g}", m.radius);
        std::vector<std::pair<std::uint64_t, CopyImage>> held;
        for (CopyRecord const& c : group) {
            held.emplace_back(c.block, c.image);
            BlockRecord const* b = findBlock(c.block);
            if (b != nullptr && !copyNeeded(b->box, m.position, c.image, rOut, m_period))
                report(u + where(c.where()) + " holds a copy, but " + grain +
                       " does not overlap it");
        }
        std::sort(held.begin(), held.end());
        for (std::size_t i = 1; i < held.size(); ++i)
            if (held[i] == held[i - 1])
                report(u + "block " + domain::BlockId::fromRaw(held[i].first).toString() +
                       " image " + img(held[i].second) + " holds more than one copy");
        forEachNeeded(m.position, rIn, [&](std::uint64_t id, CopyImage const& k) {
            if (!std::binary_search(held.begin(), held.end(), std::pair(id, k)))
                report(u + where(CopyRef{m_blocks.at(id).rank, id, k}) + " overlaps " + grain +
                       " but holds no copy of it");
        });
    }

    /// Calls f(block, image) for every block image that copyNeeded(box, x, image, r) selects:
    /// images from the ball's extent on periodic axes, blocks binned by root block.
    template <class F>
    void forEachNeeded(core::Vec3 const& x, double r, F&& f) const {
        core::AABB const& domain = m_geometry.domain();
        core::Vec3 const extent = domain.extent();
        double const reach = r * (1.0 + 2.0 * ParticleSync::kOverlapMargin);
        std::array<int, 3> kLo{0, 0, 0}, kHi{0, 0, 0};
        for (int a = 0; a < 3; ++a) {
            if (m_period[a] <= 0.0 || m_wrapped[static_cast<std::size_t>(a)])
                continue; // (no copy through a wrapped face: the cells find those pairs)
            auto const lo = std::floor((domain.min[a] - x[a] - reach) / m_period[a]);
            auto const hi = std::ceil((domain.max[a] - x[a] + reach) / m_period[a]);
            kLo[static_cast<std::size_t>(a)] = static_cast<int>(std::max<double>(lo, -kMaxImage));
            kHi[static_cast<std::size_t>(a)] = static_cast<int>(std::min<double>(hi, kMaxImage));
        }
        CopyImage k{};
        for (int i = kLo[0]; i <= kHi[0]; ++i)
            for (int j = kLo[1]; j <= kHi[1]; ++j)
                for (int l = kLo[2]; l <= kHi[2]; ++l) {
                    k = {static_cast<std::int8_t>(i), static_cast<std::int8_t>(j),
                         static_cast<std::int8_t>(l)};
                    core::Vec3 const y = localPosition(x, k, m_period);
                    std::array<std::int64_t, 3> lo{}, hi{};
                    bool inside = true;
                    for (int a = 0; a < 3; ++a) {
                        auto const n = m_geometry.rootBlocks()[static_cast<std::size_t>(a)];
                        double const edge = extent[a] / n;
                        double const c0 = std::floor((y[a] - reach - domain.min[a]) / edge) - 1.0;
                        double const c1 = std::floor((y[a] + reach - domain.min[a]) / edge) + 1.0;
                        inside = inside && c1 >= 0.0 && c0 < n;
                        lo[static_cast<std::size_t>(a)] =
                            static_cast<std::int64_t>(std::max(c0, 0.0));
                        hi[static_cast<std::size_t>(a)] =
                            static_cast<std::int64_t>(std::min(c1, n - 1.0));
                    }
                    if (!inside)
                        continue;
                    for (auto c2 = lo[2]; c2 <= hi[2]; ++c2)
                        for (auto c1 = lo[1]; c1 <= hi[1]; ++c1)
                            for (auto c0 = lo[0]; c0 <= hi[0]; ++c0) {
                                auto const it = m_byRoot.find(m_geometry.rootIndex({c0, c1, c2}));
                                if (it == m_byRoot.end())
                                    continue;
                                for (std::uint64_t id : it->second)
                                    if (copyNeeded(m_blocks.at(id).box, x, k, r, m_period))
                                        f(id, k);
                            }
                }
    }

    domain::ForestGeometry const& m_geometry;
    core::Vec3 m_period;
    std::array<bool, 3> m_wrapped;
    bool m_converged;
    double m_skin = 0.0;
    std::unordered_map<std::uint64_t, BlockRecord> m_blocks;
    std::unordered_map<std::uint64_t, std::vector<std::uint64_t>> m_byRoot;
    std::vector<std::string> m_listed;
    std::size_t m_total = 0;
};

} // namespace

std::vector<std::string> checkSyncInvariants(LocalParticles const& local, core::Comm const& comm,
                                             bool spreadingConverged, double skin) {
    if (comm.size() != local.forest().rankCount())
        throw core::Error("checkSyncInvariants: the communicator has " +
                          std::to_string(comm.size()) + " ranks, the forest " +
                          std::to_string(local.forest().rankCount()));
    auto const gathered = comm.gatherStrings(packLocal(local), 0);
    std::string verdict;
    if (comm.rank() == 0) {
        domain::BlockForest const& forest = local.forest();
        core::Vec3 period = core::Vec3::Zero();
        for (int a = 0; a < 3; ++a)
            if (forest.periodic()[static_cast<std::size_t>(a)])
                period[a] = forest.domain().extent()[a];
        std::vector<CopyRecord> copies;
        std::vector<std::pair<std::uint64_t, BlockRecord>> blocks;
        for (std::size_t r = 0; r < gathered.size(); ++r)
            unpackRank(static_cast<int>(r), gathered[r], copies, blocks);
        Checker checker(forest.geometry(), period, wrappedAxes(forest), spreadingConverged, skin);
        checker.addBlocks(blocks);
        checker.run(copies);
        core::SendBuffer b;
        b << checker.result();
        verdict.assign(reinterpret_cast<char const*>(b.data()), b.size());
    }
    comm.broadcast(verdict, 0);
    std::vector<std::byte> data(verdict.size());
    if (!verdict.empty())
        std::memcpy(data.data(), verdict.data(), verdict.size());
    core::RecvBuffer in(std::move(data));
    return core::read<std::vector<std::string>>(in);
}

void requireSyncInvariants(LocalParticles const& local, core::Comm const& comm,
                           bool spreadingConverged, std::string_view where, double skin) {
    auto const violations = checkSyncInvariants(local, comm, spreadingConverged, skin);
    if (violations.empty())
        return;
    std::string msg = fmt::format("synchronisation invariants violated ({}):", where);
    for (std::string const& v : violations)
        msg += "\n  " + v;
    throw core::Error(msg);
}

} // namespace regolith::particles
