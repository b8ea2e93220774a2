// SparseExchange (NBX): random directed patterns with 0 B .. 1 MiB messages over several
// rounds on one object, a silent round, exact counters, ordering, misuse; callbacks that
// throw and a message over the limit (every rank throws the same error), each followed by
// calls on the same object that must deliver exactly their own data.
#include "core/mpi/SparseExchange.hpp"

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

constexpr int kRounds = 5;

/// What this rank sends in `round`, as SparseExchange counts it (its header).
CommStats expectedStats(ExchangePattern const& pat, int me, int round) {
    CommStats s;
    for (int q = 0; q < pat.ranks; ++q) {
        if (q == me || !pat.sends(me, q, round))
            continue;
        s.messages += 1;
        s.bytes += pat.size(me, q, round);
        ++s.peers;
    }
    return s;
}

} // namespace

TEST(SparseExchange, RandomPatternsArriveIntactWithExactCounters) {
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    for (std::uint64_t const seed : {21u, 22u}) {
        ExchangePattern const pat{p, seed};
        SparseExchange ex(world);
        CommStats total;
        for (int round = 0; round < kRounds; ++round) {
            // Destinations in a scrambled order: delivery order must not depend on it.
            for (int k = 0; k < p; ++k) {
                int const q = (k * 5 + me + round) % p;
                if (pat.sends(me, q, round))
                    pat.pack(ex.sendBuffer(q), me, q, round);
            }
            ex.start();
            std::vector<int> expectedFrom;
            for (int src = 0; src < p; ++src)
                if (pat.sends(src, me, round))
                    expectedFrom.push_back(src);
            std::vector<int> from;
            ex.wait([&](int src, RecvBuffer& in) {
                from.push_back(src);
                EXPECT_EQ(pat.verify(in, src, me, round), "") << "seed " << seed;
            });
            EXPECT_EQ(from, expectedFrom) << "round " << round;

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

        std::uint64_t allMessages = 0;
        std::uint64_t allBytes = 0;
        for (int r = 0; r < p; ++r)
            for (int round = 0; round < kRounds; ++round) {
                allMessages += expectedStats(pat, r, round).messages;
                allBytes += expectedStats(pat, r, round).bytes;
            }
        CommTotals const g = ex.counters().reduce(world);
        EXPECT_EQ(g.messages, allMessages);
        EXPECT_EQ(g.bytes, allBytes);
    }
}

TEST(SparseExchange, ManyQuickRoundsKeepRoundsApart) {
    // Rank 0 talks to everyone, everyone to rank 0, odd rounds also to the next rank: a rank
    // that leaves the barrier early sends its next round while others still probe.
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    SparseExchange ex(world);
    for (int round = 0; round < 80; ++round) {
        std::vector<int> dests;
        if (me == 0)
            for (int q = 0; q < p; ++q)
                dests.push_back(q);
        else
            dests.push_back(0);
        if (round % 2 == 1)
            dests.push_back((me + 1) % p);
        std::sort(dests.begin(), dests.end());
        dests.erase(std::unique(dests.begin(), dests.end()), dests.end());
        for (int const q : dests)
            ex.sendBuffer(q) << me << round;
        ex.start();

        std::vector<int> expectedFrom;
        for (int src = 0; src < p; ++src)
            if (src == 0 || me == 0 || (round % 2 == 1 && (src + 1) % p == me))
                expectedFrom.push_back(src);
        std::vector<int> from;
        for (auto& m : ex.wait()) {
            from.push_back(m.rank);
            EXPECT_EQ(read<int>(m.buffer), m.rank);
            EXPECT_EQ(read<int>(m.buffer), round);
            EXPECT_TRUE(m.buffer.exhausted());
        }
        EXPECT_EQ(from, expectedFrom) << "round " << round;
    }
}

TEST(SparseExchange, EmptyBufferIsDeliveredAsNotification) {
    Comm world;
    int const p = world.size();
    SparseExchange ex(world);
    static_cast<void>(ex.sendBuffer((world.rank() + 1) % p)); // opened, left empty
    ex.start();
    auto msgs = ex.wait();
    EXPECT_EQ(msgs.size(), 1u);
    for (auto& m : msgs) {
        EXPECT_EQ(m.rank, (world.rank() + p - 1) % p);
        EXPECT_EQ(m.buffer.size(), 0u);
    }
    CommStats const expected =
        p == 1 ? CommStats{} : CommStats{.messages = 1, .bytes = 0, .peers = 1};
    EXPECT_EQ(ex.counters().last(), expected);
}

TEST(SparseExchange, FlagIsRaisedOnEveryRankIffSomeRankRaisedIt) {
    Comm world;
    int const p = world.size();
    SparseExchange ex(world);
    EXPECT_FALSE(ex.flagRaised());
    EXPECT_THROW(ex.raiseFlag(), Error) << "no call in flight";
    // Call c: rank c % p raises it (for c < p), none in call p; messages go round a ring.
    for (int c = 0; c <= p; ++c) {
        ex.sendBuffer((world.rank() + 1) % p) << c;
        ex.start();
        if (c < p && world.rank() == c)
            ex.raiseFlag();
        auto msgs = ex.wait();
        ASSERT_EQ(msgs.size(), 1u);
        EXPECT_EQ(read<int>(msgs[0].buffer), c);
        EXPECT_EQ(ex.flagRaised(), c < p) << "call " << c;
    }
}

TEST(SparseExchange, MisuseThrows) {
    Comm world;
    SparseExchange ex(world);
    EXPECT_THROW(ex.sendBuffer(-1), Error);
    EXPECT_THROW(ex.sendBuffer(world.size()), Error);
    EXPECT_THROW(static_cast<void>(ex.wait()), Error) << "wait without start";
    ex.sendBuffer(world.rank()) << 5;
    ex.start();
    EXPECT_THROW(ex.sendBuffer(0), Error) << "buffer in flight";
    EXPECT_THROW(ex.start(), Error) << "start twice";
    auto msgs = ex.wait();
    EXPECT_EQ(msgs.size(), 1u);
    for (auto& m : msgs)
        EXPECT_EQ(read<int>(m.buffer), 5);
}

TEST(SparseExchange, DestroyedInFlightStillTakesPart) {
    Comm world;
    int const p = world.size();
    {
        SparseExchange ex(world);
        ex.sendBuffer((world.rank() + 1) % p) << world.rank();
        ex.start();
    } // the destructor completes the call, else the barrier would never finish
    SparseExchange ex(world);
    ex.sendBuffer((world.rank() + 2) % p) << world.rank();
    ex.start();
    auto msgs = ex.wait();
    EXPECT_EQ(msgs.size(), 1u);
    for (auto& m : msgs)
        EXPECT_EQ(read<int>(m.buffer), (world.rank() + 2 * p - 2) % p);
}

TEST(SparseExchange, CallbackThrowingLeavesTheObjectUsable) {
    // Round 0: every rank's callback throws at its first message; rounds 1..: rank r % p
    // throws. Each later round must deliver exactly that round's data on every rank: nothing
    // of an interrupted round may remain for the next one.
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    ExchangePattern const pat{p, 31};
    SparseExchange ex(world);
    int const rounds = 6;
    for (int round = 0; round < rounds; ++round) {
        for (int q = 0; q < p; ++q)
            if (pat.sends(me, q, round))
                pat.pack(ex.sendBuffer(q), me, q, round);
        ex.start();
        std::vector<int> expectedFrom;
        for (int src = 0; src < p; ++src)
            if (pat.sends(src, me, round))
                expectedFrom.push_back(src);
        bool const thrower = round < rounds - 2 && (round == 0 || me == round % p);
        std::vector<int> from;
        auto onMessage = [&](int src, RecvBuffer& in) {
            if (thrower)
                throw std::runtime_error("callback failed");
            from.push_back(src);
            EXPECT_EQ(pat.verify(in, src, me, round), "");
        };
        if (thrower && !expectedFrom.empty()) {
            EXPECT_THROW(ex.wait(onMessage), std::runtime_error) << "round " << round;
        } else {
            ex.wait(onMessage);
            EXPECT_EQ(from, expectedFrom) << "round " << round;
        }
        EXPECT_FALSE(ex.inFlight());
    }
    EXPECT_EQ(ex.counters().calls(), static_cast<std::uint64_t>(rounds));
}

TEST(SparseExchange, OversizedMessageFailsTheCallOnEveryRank) {
    // Over the limit: rank 1 -> (p >= 3 ? p - 1 : 0) and, for p >= 3, rank p - 1 -> 0. Every
    // rank throws the same message naming the lowest pair; the next call works.
    constexpr std::uint64_t kLimit = 256;
    Comm world;
    int const me = world.rank();
    int const p = world.size();
    SparseExchange ex(world, kLimit);
    EXPECT_EQ(ex.maxMessageBytes(), kLimit);
    auto const oversized = [p](int src, int dst) {
        return (src == 1 && dst == (p >= 3 ? p - 1 : 0)) || (p >= 3 && src == p - 1 && dst == 0);
    };
    std::vector<std::byte> const big(kLimit + 1, std::byte{7});
    for (int round = 0; round < 3; ++round) {
        bool const failing = round == 0 && p >= 2;
        std::vector<int> dests{(me + 1) % p, 0};
        if (p >= 3)
            dests.push_back(p - 1);
        std::sort(dests.begin(), dests.end());
        dests.erase(std::unique(dests.begin(), dests.end()), dests.end());
        CommStats sent;
        for (int const q : dests) {
            auto& b = ex.sendBuffer(q);
            if (failing && oversized(me, q)) {
                b.writeBytes(big.data(), big.size());
                continue;
            }
            b << me << round;
            if (q == me) // self messages have no limit
                b.writeBytes(big.data(), big.size());
            else {
                sent.messages += 1;
                sent.bytes += 2 * sizeof(int);
                ++sent.peers;
            }
        }
        EXPECT_NO_THROW(ex.start());
        EXPECT_EQ(ex.counters().last(), sent) << "a message over the limit is not sent";
        std::string error;
        std::vector<int> from;
        try {
            ex.wait([&](int src, RecvBuffer& in) {
                from.push_back(src);
                EXPECT_EQ(read<int>(in), src);
                EXPECT_EQ(read<int>(in), round);
                EXPECT_EQ(in.remaining(), src == me ? big.size() : 0u);
            });
        } catch (Error const& e) {
            error = e.what();
        }
        EXPECT_FALSE(ex.inFlight());
        if (failing) {
            EXPECT_EQ(error, "SparseExchange: rank 1 has a message for rank " +
                                 std::to_string(p >= 3 ? p - 1 : 0) +
                                 " larger than the limit of 256 bytes");
            EXPECT_TRUE(from.empty()) << "nothing of a failed call is delivered";
        } else {
            EXPECT_EQ(error, "") << "round " << round;
            std::vector<int> expectedFrom;
            for (int src = 0; src < p; ++src)
                if (src == (me + p - 1) % p || me == 0 || (me == p - 1 && p >= 3))
                    expectedFrom.push_back(src);
            EXPECT_EQ(from, expectedFrom) << "round " << round;
        }
    }
}

TEST(SparseExchange, LimitMustBeValidAndEqualOnEveryRank) {
    Comm world;
    auto const constructionError = [&world](std::uint64_t limit) -> std::string {
        try {
            SparseExchange const ex(world, limit);
        } catch (Error const& e) {
            return e.what();
        }
        return {};
    };
    EXPECT_EQ(constructionError(0), "SparseExchange: maxMessageBytes 0 not in [1, 2147483647]");
    if (world.size() >= 2) {
        EXPECT_EQ(constructionError(world.rank() == 0 ? 100 : 200),
                  "SparseExchange: maxMessageBytes differs between ranks (100 to 200)");
    }
}
