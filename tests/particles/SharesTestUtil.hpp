#pragma once
// Helpers of the batch kernels' tests: the shares a contact evaluation hands its sink, recorded
// in order, and compared bit for bit with another evaluation's; two storages' histories
// compared entry by entry.
#include "particles/storage/ParticleStorage.hpp"
#include "tests/particles/PeriodicTestUtil.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

namespace regolith::particles::test {

/// One participant's share of one contact, as a ContactSink receives it.
struct Share {
    std::size_t copy;
    Uid partner;
    Vec3 force;
    Vec3 torque;
};

/// A ContactSink that appends each share to `out`.
inline auto recordInto(std::vector<Share>& out) {
    return [&out](std::size_t k, Uid partner, Vec3 const& f, Vec3 const& t) {
        out.push_back(Share{k, partner, f, t});
    };
}

/// The same shares in the same order, forces and torques bit for bit.
inline void expectSameShares(std::vector<Share> const& got, std::vector<Share> const& expected) {
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(got[k].copy, expected[k].copy) << "share " << k;
        ASSERT_EQ(got[k].partner, expected[k].partner) << "share " << k;
        EXPECT_TRUE(sameBits(got[k].force, expected[k].force)) << "share " << k;
        EXPECT_TRUE(sameBits(got[k].torque, expected[k].torque)) << "share " << k;
    }
}

/// Every copy's history the same in both storages: partners, stamps, springs bit for bit.
inline void expectSameHistories(ParticleStorage const& got, ParticleStorage const& expected) {
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        auto const& a = expected.history(k).entries();
        auto const& b = got.history(k).entries();
        ASSERT_EQ(a.size(), b.size()) << "uid " << expected.uid(k);
        for (std::size_t e = 0; e < a.size(); ++e) {
            EXPECT_EQ(a[e].partner, b[e].partner);
            EXPECT_EQ(a[e].stamp, b[e].stamp);
            EXPECT_TRUE(sameBits(a[e].spring, b[e].spring)) << "uid " << expected.uid(k);
        }
    }
}

} // namespace regolith::particles::test
