// NeighbourExchange: random symmetric peer graphs with 0 B .. 1 MiB messages over several
// rounds on one object, exact counters, delivery order, misuse and error paths: asymmetric or
// invalid peer lists (every rank throws the same message), a message over the limit (its two
// ends throw, nobody hangs), callbacks that throw (the object stays usable).
#include "core/mpi/NeighbourExchange.hpp"

#include "core/Error.hpp"
#include "tests/core/ExchangePattern.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

using namespace regolith::core;
using regolith::testing::ExchangePattern;

namespace {

constexpr int kRounds = 5; // every (src, dst) meets an empty and a 1 MiB message (pattern)

/// What this rank sends in `round`, as NeighbourExchange counts it (its header).
CommStats expectedStats(ExchangePattern const& pat, int me, int round) {
    CommStats s;
    for (int const q : pat.peersOf(me)) {
        if (q == me)
            continue;
        std::size_t const n = pat.size(me, q, round);
        s.messages += 1 + (n > 0 ? 1 : 0);
        s.bytes += sizeof(std::uint64_t) + n;
        ++s.peers;
    }
    return s;
}

} // namespace

TEST(NeighbourExchange, RandomPatternsArriveIntactWithExactCounters) {
    Comm world;
    int const me = world.rank();
    for (std::uint64_t const seed : {11u, 12u}) {
        ExchangePattern const pat{world.size(), seed};
        auto const peers = pat.peersOf(me);
        NeighbourExchange ex(world, peers);
        EXPECT_TRUE(NeighbourExchange::peersAreSymmetric(world, peers));

        CommStats total;
        for (int round = 0; round < kRounds; ++round) {
            for (int const q : peers)
                pat.pack(ex.sendBuffer(q), me, q, round);
            ex.start();
            EXPECT_TRUE(ex.inFlight());
            std::vector<int> order;
            ex.wait([&](int from, RecvBuffer& in) {
                order.push_back(from);
                EXPECT_EQ(pat.verify(in, from, me, round), "") << "seed " << seed;
            });
            EXPECT_FALSE(ex.inFlight());
            EXPECT_EQ(order, peers) << "every peer delivered once, ascending";

            CommStats const expected = expectedStats(pat, me, round);
            EXPECT_EQ(ex.counters().last(), expected) << "round " << round;
            total.messages += expected.messages;
            total.bytes += expected.bytes;
            total.peers = std::max(total.peers, expected.peers);
        }
        EXPECT_EQ(ex.counters().calls(), static_cast<std::uint64_t>(kRounds));
        EXPECT_EQ(ex.counters().totalMessages(), total.messages);
        EXPECT_EQ(ex.counters().totalBytes(), total.bytes);
        EXPECT_EQ(ex.counters().maxPeers(), total.peers);

        // Over all ranks, from the pattern alone.
        std::uint64_t allMessages = 0;
        std::uint64_t allBytes = 0;
        int maxPeers = 0;
        for (int r = 0; r < world.size(); ++r)
            for (int round = 0; round < kRounds; ++round) {
                CommStats const s = expectedStats(pat, r, round);
                allMessages += s.messages;
                allBytes += s.bytes;
                maxPeers = std::max(maxPeers, s.peers);
            }
        CommTotals const g = ex.counters().reduce(world);
        EXPECT_EQ(g.messages, allMessages);
        EXPECT_EQ(g.bytes, allBytes);
        EXPECT_EQ(g.calls, static_cast<std::uint64_t>(kRounds));
        EXPECT_EQ(g.maxPeers, maxPeers);
    }
}

TEST(NeighbourExchange, AllToAllManyQuickRoundsKeepRoundsApart) {
    // Small messages in rapid succession: a fast rank's next round must never be mistaken
    // for the current one. Each message carries (source, round, a size varying by round).
    Comm world;
    int const me = world.rank();
    std::vector<int> all(static_cast<std::size_t>(world.size()));
    for (int r = 0; r < world.size(); ++r)
        all[static_cast<std::size_t>(r)] = r;
    NeighbourExchange ex(world, all);
    for (int round = 0; round < 60; ++round) {
        for (int const q : all) {
            auto& b = ex.sendBuffer(q);
            if ((round + me + q) % 3 != 0) // some rounds send nothing to q
                b << me << round << std::vector<int>(static_cast<std::size_t>(round % 7), q);
        }
        ex.start();
        for (auto& m : ex.wait()) {
            if ((round + m.rank + me) % 3 == 0) {
                EXPECT_TRUE(m.buffer.exhausted());
                continue;
            }
            EXPECT_EQ(read<int>(m.buffer), m.rank);
            EXPECT_EQ(read<int>(m.buffer), round);
            EXPECT_EQ(read<std::vector<int>>(m.buffer),
                      std::vector<int>(static_cast<std::size_t>(round % 7), me));
            EXPECT_TRUE(m.buffer.exhausted());
        }
    }
}

TEST(NeighbourExchange, SelfOnlyNeedsNoMpiAndIsNotCounted) {
    Comm world;
    NeighbourExchange ex(world, {world.rank()});
    ex.sendBuffer(world.rank()) << 42.5 << std::string("self");
    ex.start();
    auto msgs = ex.wait();
    ASSERT_EQ(msgs.size(), 1u);
    EXPECT_EQ(msgs[0].rank, world.rank());
    EXPECT_EQ(read<double>(msgs[0].buffer), 42.5);
    EXPECT_EQ(read<std::string>(msgs[0].buffer), "self");
    EXPECT_EQ(ex.counters().last(), CommStats{});
    EXPECT_EQ(ex.counters().calls(), 1u);
}

TEST(NeighbourExchange, MisuseThrows) {
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    // A ring without myself: the next rank is a peer, I am not (for p == 1 nothing is).
    std::vector<int> ring;
    if (p > 1) {
        ring = {(me + p - 1) % p, (me + 1) % p};
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    }
    NeighbourExchange ex(world, ring);
    EXPECT_THROW(ex.sendBuffer(me), Error) << "self is not a peer here";
    EXPECT_THROW(ex.sendBuffer(-1), Error);
    EXPECT_THROW(ex.sendBuffer(p), Error);
    EXPECT_THROW(static_cast<void>(ex.wait()), Error) << "wait without start";

    for (int const q : ring)
        ex.sendBuffer(q) << me;
    ex.start();
    if (!ring.empty()) {
        EXPECT_THROW(ex.sendBuffer(ring.front()), Error) << "buffer in flight";
    }
    EXPECT_THROW(ex.start(), Error) << "start twice";
    auto msgs = ex.wait();
    EXPECT_EQ(msgs.size(), ring.size());
    for (auto& m : msgs)
        EXPECT_EQ(read<int>(m.buffer), m.rank);

    // Every rank throws (after the collective duplicate), so nobody is left waiting.
    EXPECT_THROW(static_cast<void>(NeighbourExchange(world, std::vector<int>{p})), Error)
        << "out of range";
    EXPECT_THROW(static_cast<void>(NeighbourExchange(world, std::vector<int>{0, 0})), Error)
        << "not strictly ascending";
}

TEST(NeighbourExchange, SymmetryCheckSeesOneWayLinks) {
    Comm world;
    int const p = world.size();
    // Directed ring me -> me+1: symmetric only if p <= 2.
    std::vector<int> const next{(world.rank() + 1) % p};
    EXPECT_EQ(NeighbourExchange::peersAreSymmetric(world, next), p <= 2);
    std::vector<int> const bad{p};
    EXPECT_FALSE(NeighbourExchange::peersAreSymmetric(world, bad));
}

TEST(NeighbourExchange, ThrowingCallbackCompletesTheCallAndLeavesItUsable) {
    Comm world;
    ExchangePattern const pat{world.size(), 99};
    auto const peers = pat.peersOf(world.rank());
    NeighbourExchange ex(world, peers);
    for (int round = 0; round < 2; ++round) {
        for (int const q : peers)
            pat.pack(ex.sendBuffer(q), world.rank(), q, round);
        ex.start();
        if (round == 0 && !peers.empty()) {
            EXPECT_THROW(ex.wait([](int, RecvBuffer&) { throw std::runtime_error("user"); }),
                         std::runtime_error);
            EXPECT_FALSE(ex.inFlight());
        } else {
            ex.wait([&](int from, RecvBuffer& in) {
                EXPECT_EQ(pat.verify(in, from, world.rank(), round), "");
            });
        }
    }
}

TEST(NeighbourExchange, DestroyedInFlightCompletesItsCall) {
    Comm world;
    ExchangePattern const pat{world.size(), 7};
    auto const peers = pat.peersOf(world.rank());
    {
        NeighbourExchange ex(world, peers);
        for (int const q : peers)
            pat.pack(ex.sendBuffer(q), world.rank(), q, 0);
        ex.start();
    } // destructor drains
    NeighbourExchange ex(world, peers);
    for (int const q : peers)
        pat.pack(ex.sendBuffer(q), world.rank(), q, 1);
    ex.start();
    for (auto& m : ex.wait())
        EXPECT_EQ(pat.verify(m.buffer, m.rank, world.rank(), 1), "");
}

namespace {

/// The message of the core::Error the constructor throws on this rank, "" if it does not.
std::string constructionError(Comm const& world, std::vector<int> peers,
                              std::uint64_t limit = NeighbourExchange::kMaxMessageBytes) {
    try {
        NeighbourExchange const ex(world, std::move(peers), limit);
    } catch (Error const& e) {
        return e.what();
    }
    return {};
}

std::string asymmetry(int lister, int other) {
    return "NeighbourExchange: asymmetric peer lists: rank " + std::to_string(lister) +
           " lists rank " + std::to_string(other) + ", but rank " + std::to_string(other) +
           " does not list rank " + std::to_string(lister);
}

} // namespace

// Every rank checks its own message against the same expected text, so a pass at every rank
// count proves that all ranks threw and agree on the pair.
TEST(NeighbourExchange, AsymmetricPeerListsThrowOnEveryRankNamingOnePair) {
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    std::vector<int> all(static_cast<std::size_t>(p));
    for (int r = 0; r < p; ++r)
        all[static_cast<std::size_t>(r)] = r;

    // Everyone lists everyone, except that the last rank leaves out rank 0.
    std::vector<int> dropped = all;
    if (p >= 2 && me == p - 1)
        dropped.erase(dropped.begin());
    std::string const expectDropped = p >= 2 ? asymmetry(0, p - 1) : "";
    EXPECT_EQ(constructionError(world, dropped), expectDropped);
    EXPECT_EQ(NeighbourExchange::peersAreSymmetric(world, dropped), p < 2);

    // A directed ring (plus self): every rank is listed exactly as often as it lists, so a
    // count of listers alone would pass it; symmetric only for p <= 2.
    std::vector<int> ring{me, (me + 1) % p};
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    EXPECT_EQ(constructionError(world, ring), p >= 3 ? asymmetry(0, 1) : "");
    EXPECT_EQ(NeighbourExchange::peersAreSymmetric(world, ring), p <= 2);

    // Rank 0 is listed by everyone but lists only itself: found by the census on rank 0.
    std::vector<int> star{0};
    if (me != 0)
        star.push_back(me);
    EXPECT_EQ(constructionError(world, star), p >= 2 ? asymmetry(1, 0) : "");

    // One rank's list is invalid: everybody reports that rank's problem.
    std::vector<int> invalid{me};
    if (me == p - 1)
        invalid.push_back(p);
    EXPECT_EQ(constructionError(world, invalid),
              "NeighbourExchange: rank " + std::to_string(p - 1) + ": peer " + std::to_string(p) +
                  " out of range [0, " + std::to_string(p) + ")");

    // The lists that pass construct an exchange that works.
    EXPECT_EQ(constructionError(world, all), "");
}

TEST(NeighbourExchange, LimitMustBeValidAndEqualOnEveryRank) {
    Comm world;
    int const p = world.size();
    EXPECT_EQ(constructionError(world, {world.rank()}, 0),
              "NeighbourExchange: rank 0: maxMessageBytes 0 not in [1, 2147483647]");
    if (p >= 2) {
        EXPECT_EQ(constructionError(world, {world.rank()}, world.rank() == 0 ? 100 : 200),
                  "NeighbourExchange: maxMessageBytes differs between ranks (100 to 200)");
    }
}

TEST(NeighbourExchange, OversizedMessageFailsTheCallOnItsTwoEndsOnly) {
    // Rank 1 has a message over the limit for rank 0. Both throw from wait() with the same
    // message and nobody hangs; the other ranks receive everything; then the object works.
    constexpr std::uint64_t kLimit = 256;
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    std::vector<int> all(static_cast<std::size_t>(p));
    for (int r = 0; r < p; ++r)
        all[static_cast<std::size_t>(r)] = r;
    NeighbourExchange ex(world, all, kLimit);
    EXPECT_EQ(ex.maxMessageBytes(), kLimit);
    int const sender = 1;
    int const receiver = 0;
    std::string const expected = "NeighbourExchange: rank 1 has a 257-byte message for rank 0, "
                                 "above the limit of 256 bytes";
    for (int round = 0; round < 4; ++round) {
        bool const failing = round == 0 && p >= 2;
        for (int const q : all) {
            auto& b = ex.sendBuffer(q);
            b << me << round;
            if (failing && me == sender && q == receiver)
                b.writeBytes(std::vector<std::byte>(257 - 2 * sizeof(int)).data(),
                             257 - 2 * sizeof(int));
            if (q == me) // self messages have no limit
                b << std::vector<char>(1000, 's');
        }
        EXPECT_NO_THROW(ex.start());
        std::vector<int> from;
        std::string error;
        try {
            ex.wait([&](int src, RecvBuffer& in) {
                from.push_back(src);
                EXPECT_EQ(read<int>(in), src);
                EXPECT_EQ(read<int>(in), round);
                if (src == me) {
                    EXPECT_EQ(read<std::vector<char>>(in), std::vector<char>(1000, 's'));
                }
                EXPECT_TRUE(in.exhausted());
            });
        } catch (Error const& e) {
            error = e.what();
        }
        EXPECT_FALSE(ex.inFlight());
        bool const end = failing && (me == sender || me == receiver);
        EXPECT_EQ(error, end ? expected : "") << "round " << round;
        std::vector<int> expectFrom = all;
        if (end)
            expectFrom = me == sender ? std::vector<int>{} : std::vector<int>{0};
        EXPECT_EQ(from, expectFrom) << "round " << round;
        if (failing && me == sender) { // sizes to all others, payloads to all but rank 0
            EXPECT_EQ(ex.counters().last().messages, static_cast<std::uint64_t>(2 * p - 3));
        }
    }
}

TEST(NeighbourExchange, CallbackThrowingOnOneRankLeavesEveryRankUsable) {
    // In round r, rank r % p throws from its second delivery; the others are unaffected, and
    // every later round still delivers exactly the right data to every rank.
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    ExchangePattern const pat{p, 1234};
    auto const peers = pat.peersOf(me);
    NeighbourExchange ex(world, peers);
    int const rounds = std::min(p, 4) + 2;
    for (int round = 0; round < rounds; ++round) {
        for (int const q : peers)
            pat.pack(ex.sendBuffer(q), me, q, round);
        ex.start();
        bool const thrower = round < rounds - 2 && me == round % p;
        std::size_t delivered = 0;
        auto onMessage = [&](int from, RecvBuffer& in) {
            if (thrower && delivered == std::min<std::size_t>(1, peers.size() - 1))
                throw std::runtime_error("callback failed");
            ++delivered;
            EXPECT_EQ(pat.verify(in, from, me, round), "") << "round " << round;
        };
        if (thrower && !peers.empty()) {
            EXPECT_THROW(ex.wait(onMessage), std::runtime_error);
            EXPECT_EQ(delivered, std::min<std::size_t>(1, peers.size() - 1));
        } else {
            ex.wait(onMessage);
            EXPECT_EQ(delivered, peers.size()) << "round " << round;
        }
        EXPECT_FALSE(ex.inFlight());
    }
    EXPECT_EQ(ex.counters().calls(), static_cast<std::uint64_t>(rounds));
}

TEST(CommStats, AddingACallSumsMessagesAndBytesAndKeepsTheMostPeers) {
    // The synchronisation adds the calls of several exchanges into one per step.
    CommStats call{3, 100, 2};
    call += CommStats{2, 40, 1};
    EXPECT_EQ(call, (CommStats{5, 140, 2}));
    call += CommStats{0, 0, 5};
    EXPECT_EQ(call, (CommStats{5, 140, 5}));
}
