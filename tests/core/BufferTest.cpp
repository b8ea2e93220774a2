// Pack/unpack round trips for every supported type; short and corrupt buffers throw.
#include "core/mpi/Buffer.hpp"

#include "core/math/Vec3.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

using namespace regolith::core;

namespace {

struct Pod {
    std::uint64_t uid;
    double x;
    int flags;
    bool operator==(Pod const&) const = default;
};
enum class Kind : std::uint8_t { A = 1, B = 7 };

RecvBuffer toRecv(SendBuffer& s) {
    return RecvBuffer(s.release());
}

} // namespace

TEST(Buffer, RoundTripsEverySupportedType) {
    SendBuffer s;
    Pod const pod{42, 3.5, -7};
    std::vector<double> const doubles{1.0, -2.5, 1e300};
    std::vector<std::string> const strings{"", "shadow", std::string(1000, 'x')};
    std::vector<std::vector<int>> const nested{{}, {1}, {2, 3, 4}};
    std::array<std::string, 2> const arr{"a", "bc"};
    Vec3 const v(1.0, 2.0, 3.0);
    Quat const q(0.5, 0.5, 0.5, 0.5);
    s << std::uint64_t{0xdeadbeefcafef00dULL} << 'c' << true << Kind::B << pod << doubles << strings
      << nested << arr << v << q << std::string("tail");

    RecvBuffer r = toRecv(s);
    EXPECT_EQ(read<std::uint64_t>(r), 0xdeadbeefcafef00dULL);
    EXPECT_EQ(read<char>(r), 'c');
    EXPECT_EQ(read<bool>(r), true);
    EXPECT_EQ(read<Kind>(r), Kind::B);
    EXPECT_EQ(read<Pod>(r), pod);
    EXPECT_EQ(read<std::vector<double>>(r), doubles);
    EXPECT_EQ(read<std::vector<std::string>>(r), strings);
    EXPECT_EQ((read<std::vector<std::vector<int>>>(r)), nested);
    EXPECT_EQ((read<std::array<std::string, 2>>(r)), arr);
    EXPECT_EQ(read<Vec3>(r), v);
    EXPECT_TRUE(read<Quat>(r).coeffs() == q.coeffs());
    EXPECT_EQ(read<std::string>(r), "tail");
    EXPECT_TRUE(r.exhausted());
}

TEST(Buffer, TruncatedBufferThrowsAtEveryCut) {
    SendBuffer s;
    s << 1.0 << std::vector<int>{1, 2, 3} << std::string("hello");
    auto const full = s.release();
    for (std::size_t cut = 0; cut < full.size(); ++cut) {
        RecvBuffer r(std::vector<std::byte>(full.begin(), full.begin() + static_cast<long>(cut)));
        EXPECT_THROW(
            {
                (void)read<double>(r);
                (void)read<std::vector<int>>(r);
                (void)read<std::string>(r);
            },
            BufferError)
            << "cut at " << cut;
    }
}

TEST(Buffer, CorruptLengthThrowsWithoutAllocating) {
    SendBuffer s;
    s << std::uint64_t{1ULL << 60} << 1.0; // a length prefix far beyond the payload
    RecvBuffer r = toRecv(s);
    try {
        (void)read<std::vector<double>>(r);
        FAIL() << "expected BufferError";
    } catch (BufferError const& e) {
        EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
    }
}

TEST(Buffer, ShortReadMessageNamesOffsetAndSize) {
    SendBuffer s;
    s << 1;
    RecvBuffer r = toRecv(s);
    try {
        (void)read<double>(r);
        FAIL() << "expected BufferError";
    } catch (BufferError const& e) {
        std::string const msg = e.what();
        EXPECT_NE(msg.find("too short"), std::string::npos) << msg;
        EXPECT_NE(msg.find("4-byte buffer"), std::string::npos) << msg;
    }
}

TEST(Buffer, ASendBufferClearedAndRefilledHoldsOnlyTheNewBytes) {
    SendBuffer s;
    s << std::vector<double>(1000, 1.0); // grows the storage
    s.clear();
    EXPECT_TRUE(s.empty());
    s << 7 << 2.5;
    EXPECT_EQ(s.size(), sizeof(int) + sizeof(double));
    EXPECT_EQ(s.bytes().size(), s.size());
    RecvBuffer r = toRecv(s);
    EXPECT_EQ(r.size(), sizeof(int) + sizeof(double));
    EXPECT_EQ(read<int>(r), 7);
    EXPECT_EQ(read<double>(r), 2.5);
    EXPECT_TRUE(r.exhausted());
    EXPECT_TRUE(s.empty()) << "release() leaves the buffer empty";
}

TEST(Buffer, ARecvBufferOnLargerStorageReadsOnlyItsMessage) {
    SendBuffer s;
    s << 1 << 2 << 3;
    std::vector<std::byte> storage = s.release();
    storage.resize(storage.size() + 64, std::byte{0xff}); // a longer earlier message's tail
    RecvBuffer r(std::move(storage), 2 * sizeof(int));
    EXPECT_EQ(read<int>(r), 1);
    EXPECT_EQ(read<int>(r), 2);
    EXPECT_TRUE(r.exhausted());
    EXPECT_THROW(read<int>(r), BufferError) << "the tail beyond the message is not readable";
    std::vector<std::byte> const back = r.takeStorage();
    EXPECT_EQ(back.size(), 3 * sizeof(int) + 64) << "the storage comes back whole, for reuse";
    EXPECT_EQ(r.size(), 0U);
}

TEST(Buffer, AMovedFromRecvBufferIsEmpty) {
    SendBuffer s;
    s << 1.5;
    RecvBuffer a = toRecv(s);
    RecvBuffer b(std::move(a));
    EXPECT_EQ(a.size(), 0U); // a moved-from buffer is specified empty
    EXPECT_TRUE(a.exhausted());
    EXPECT_THROW(read<double>(a), BufferError);
    EXPECT_EQ(read<double>(b), 1.5);
}
