// agreeOnInputError: an InputError seen by some ranks only becomes the same InputError on
// every rank (the lowest failing rank's message); success and other errors pass through.
#include "core/mpi/AgreeOnInputError.hpp"

#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

using regolith::core::agreeOnInputError;
using regolith::core::Comm;
using regolith::core::InputError;

namespace {

/// The InputError message agreeOnInputError throws here, or "(none)".
std::string outcome(Comm const& world, std::function<void()> const& action) {
    try {
        agreeOnInputError(world, action);
    } catch (InputError const& e) {
        return e.what();
    }
    return "(none)";
}

} // namespace

TEST(AgreeOnInputError, SuccessEverywhereThrowsNothing) {
    Comm world;
    int calls = 0;
    EXPECT_EQ(outcome(world, [&] { ++calls; }), "(none)");
    EXPECT_EQ(calls, 1);
}

TEST(AgreeOnInputError, SomeRanksFailingGiveTheLowestFailingRanksMessageEverywhere) {
    Comm world;
    // The upper half of the ranks fail (rank 0 alone on one rank), each with its own message.
    int const firstFailing = world.size() / 2;
    auto const action = [&] {
        if (world.rank() >= firstFailing)
            throw InputError(fmt::format("particles[0].path: cannot open 'p{}.csv'", world.rank()));
    };
    EXPECT_EQ(outcome(world, action),
              fmt::format("particles[0].path: cannot open 'p{}.csv'", firstFailing));
}

TEST(AgreeOnInputError, OnlyTheLastRankFailing) {
    Comm world;
    int const last = world.size() - 1;
    EXPECT_EQ(outcome(world,
                      [&] {
                          if (world.rank() == last)
                              throw InputError("only the last rank sees this");
                      }),
              "only the last rank sees this");
}

TEST(AgreeOnInputError, AnEmptyMessageIsReplaced) {
    Comm world;
    EXPECT_EQ(outcome(world,
                      [&] {
                          if (world.rank() == 0)
                              throw InputError("");
                      }),
              "unknown input error");
}

TEST(AgreeOnInputError, OtherErrorsAreNotTurnedIntoInputErrors) {
    Comm world;
    // Thrown on every rank, so no rank waits in the agreement; must stay a core::Error.
    bool sawPlainError = false;
    try {
        agreeOnInputError(world, [] { throw regolith::core::Error("corrupt message"); });
    } catch (InputError const&) {
    } catch (regolith::core::Error const& e) {
        sawPlainError = std::string(e.what()) == "corrupt message";
    }
    EXPECT_TRUE(sawPlainError);
}
