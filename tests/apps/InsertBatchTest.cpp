// The batch size of a pour (`[[insert]]` with a rate): rate x every x dt rounded up, the
// product's rounding above a whole number not counted as a grain more.
#include "apps/regolith/InsertSection.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace {

using regolith::apps::batchSize;
using regolith::particles::InsertSpec;

InsertSpec pour(std::int64_t count, double rate, std::int64_t every) {
    InsertSpec spec;
    spec.count = count;
    spec.rate = rate;
    spec.every = every;
    return spec;
}

TEST(InsertBatch, WholeProductIsNotRoundedUpByItsRounding) {
    // The rotating drum's pour: 5000 x 500 x 2e-5 = 50.00000000000001 in doubles.
    ASSERT_GT(5000.0 * 500.0 * 2e-5, 50.0);
    EXPECT_EQ(batchSize(pour(2500, 5000.0, 500), 2e-5), 50);
    EXPECT_EQ(batchSize(pour(400, 4000.0, 50), 1e-3), 200);
}

TEST(InsertBatch, FractionRoundsUpAndCountBounds) {
    EXPECT_EQ(batchSize(pour(2500, 5050.0, 500), 2e-5), 51); // 50.5
    EXPECT_EQ(batchSize(pour(2500, 5000.0, 501), 2e-5), 51); // 50.1
    EXPECT_EQ(batchSize(pour(30, 5000.0, 500), 2e-5), 30);   // at most count
    EXPECT_EQ(batchSize(pour(2500, 1.0, 1), 1e-3), 1);       // at least one grain
    InsertSpec all;
    all.count = 77; // no rate: everything in the first batch
    EXPECT_EQ(batchSize(all, 1e-3), 77);
}

} // namespace
