// NNS, SOS and hybrid side by side on a gas of small grains only: the same moves give the
// same copies -- the same (block, uid, image, master?) on every rank -- with the same bits,
// after every step, and the same contacts per block.
#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <memory>
#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;

namespace {

struct Run {
    Run(Comm const& comm, domain::BlockForest const& forest, SyncMethod method)
        : local(forest)
        , sync(comm, forest, SyncConfig{method, false}) {}
    LocalParticles local;
    ParticleSync sync;
};

/// (uid_i, uid_j, image_j - image_i) of every contact each local block evaluates, sorted.
std::vector<std::tuple<std::uint64_t, Uid, Uid, CopyImage>> contacts(LocalParticles const& local,
                                                                     PeriodicFrame const& frame) {
    std::vector<std::tuple<std::uint64_t, Uid, Uid, CopyImage>> out;
    ContactDetector detector;
    ContactList list;
    WallList const walls;
    for (BlockParticles const& bp : local.blocks()) {
        ParticleStorage const& ps = bp.particles;
        detector.detect(ps, walls, bp.block->aabb, frame, list);
        for (Contact const& c : list.pairs)
            out.emplace_back(bp.block->id.raw(), ps.uid(c.i), ps.uid(c.j),
                             subtractImages(ps.image(c.j), ps.image(c.i)));
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Positions and velocities of every copy, in copySet order.
std::vector<Vec3> states(LocalParticles const& local) {
    std::vector<std::tuple<std::uint64_t, Uid, CopyImage, Vec3, Vec3>> s;
    for (BlockParticles const& bp : local.blocks())
        for (std::size_t i = 0; i < bp.particles.size(); ++i)
            s.emplace_back(bp.block->id.raw(), bp.particles.uid(i), bp.particles.image(i),
                           bp.particles.position(i), bp.particles.velocity(i));
    std::sort(s.begin(), s.end(), [](auto const& a, auto const& b) {
        return std::tie(std::get<0>(a), std::get<1>(a), std::get<2>(a)) <
               std::tie(std::get<0>(b), std::get<1>(b), std::get<2>(b));
    });
    std::vector<Vec3> out;
    for (auto const& t : s) {
        out.push_back(std::get<3>(t));
        out.push_back(std::get<4>(t));
    }
    return out;
}

void sideBySide(std::array<int, 3> blocks, bool periodic) {
    Comm world;
    AABB const domain{Vec3::Zero(), Vec3(9, 9, 9)};
    domain::BlockForest const forest(world,
                                     forestSpec(domain.min, domain.max, blocks, allAxes(periodic)));
    PeriodicFrame const frame(forest);
    std::ostringstream label;
    label << blocks[0] << "x" << blocks[1] << "x" << blocks[2]
          << (periodic ? " periodic" : " open");
    std::vector<std::unique_ptr<Run>> runs;
    for (SyncMethod m : {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid})
        runs.push_back(std::make_unique<Run>(world, forest, m));
    // Dense enough for contacts: 250 grains of radius 0.3-0.7 in 729 volume units.
    auto const gas = randomGas(domain, 250, 0.3, 0.7, 1.0, 5);
    for (auto& r : runs) {
        addAll(r->local, world, gas);
        r->sync.syncUntilConverged(r->local);
    }
    std::size_t contactsSeen = 0;
    for (int step = 0; step <= 20; ++step) {
        if (step > 0)
            for (auto& r : runs) {
                drift(r->local, 0.08);
                r->sync.sync(r->local);
            }
        std::string const where = label.str() + " step " + std::to_string(step);
        CopySet const reference = copySet(runs[0]->local);
        std::vector<Vec3> const bits = states(runs[0]->local);
        auto const refContacts = contacts(runs[0]->local, frame);
        contactsSeen += refContacts.size();
        for (std::size_t k = 1; k < runs.size(); ++k) {
            std::string const m = where + " " + methodName(runs[k]->sync.config().method);
            EXPECT_EQ(copySet(runs[k]->local), reference) << m;
            std::vector<Vec3> const other = states(runs[k]->local);
            bool same = other.size() == bits.size();
            for (std::size_t i = 0; same && i < bits.size(); ++i)
                same = sameBits(other[i], bits[i]);
            EXPECT_TRUE(same) << m << ": copies differ in their bits";
            EXPECT_EQ(contacts(runs[k]->local, frame), refContacts) << m;
        }
        auto const v = checkSyncInvariants(runs[0]->local, world, true);
        EXPECT_TRUE(v.empty()) << where << joined(v);
    }
    EXPECT_GT(
        world.allReduce(static_cast<std::uint64_t>(contactsSeen), regolith::core::ReduceOp::Sum),
        0U)
        << label.str() << ": the gas should have contacts";
}

} // namespace

TEST(SideBySide, NnsSosAndHybridAgreeOnSmallGrains) {
    sideBySide({3, 3, 3}, true);
    sideBySide({3, 3, 3}, false);
    sideBySide({4, 2, 1}, true);
}
