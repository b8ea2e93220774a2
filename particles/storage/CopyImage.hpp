#pragma once
/// Which periodic copy of a particle a stored copy is. Every copy stores the master's
/// canonical state bit for bit (position inside the domain); `image` says where the copy sits
/// in the frame of the block that holds it: local position = position + imageOffset(image).
/// Keeping the canonical bits and an integer image (instead of a shifted position) makes
/// contact geometry independent of the block that evaluates it (reproducible mode), and lets
/// a block that is its own periodic neighbour hold a particle and its image side by side.
#include "core/math/Vec3.hpp"
#include "particles/storage/Uid.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace regolith::particles {

/// Whole domain periods per axis; 0 on a non-periodic axis.
using CopyImage = std::array<std::int8_t, 3>;

inline constexpr CopyImage kNoImage{0, 0, 0};
/// Images beyond +-kMaxImage are refused (a grain would reach several periods away).
inline constexpr int kMaxImage = 7;

[[nodiscard]] constexpr bool isZero(CopyImage const& k) {
    return k[0] == 0 && k[1] == 0 && k[2] == 0;
}

/// a == b without a call: GCC 12 compiles std::array<std::int8_t, 3>'s operator== to a call of
/// memcmp (3 bytes), and images are compared in every (uid, image) look-up, holder list and
/// sent cache of the synchronisation (1.4 % of the SOS gas's profile on two ranks).
[[nodiscard]] constexpr bool sameImage(CopyImage const& a, CopyImage const& b) {
    return ((a[0] ^ b[0]) | (a[1] ^ b[1]) | (a[2] ^ b[2])) == 0;
}

/// k * period per axis [length]; `period` is the domain extent on periodic axes (any value on
/// the others: their image is 0).
[[nodiscard]] inline core::Vec3 imageOffset(CopyImage const& k, core::Vec3 const& period) {
    return {k[0] * period[0], k[1] * period[1], k[2] * period[2]};
}

/// The copy's position in the frame of its holder. Always computed this way (never as a
/// shifted local position), so that every rank predicts the same bits.
[[nodiscard]] inline core::Vec3 localPosition(core::Vec3 const& canonical, CopyImage const& k,
                                              core::Vec3 const& period) {
    return isZero(k) ? canonical : core::Vec3(canonical + imageOffset(k, period));
}

namespace copy_image_detail {
/// Throws core::Error for the first axis of `k` beyond +-kMaxImage (out of line: never taken
/// in a valid scene, so the inline callers stay small).
[[noreturn]] void throwBeyondMaxImage(std::array<int, 3> const& k);

[[nodiscard]] inline CopyImage checked(std::array<int, 3> const& k) {
    if (k[0] < -kMaxImage || k[0] > kMaxImage || k[1] < -kMaxImage || k[1] > kMaxImage ||
        k[2] < -kMaxImage || k[2] > kMaxImage) [[unlikely]]
        throwBeyondMaxImage(k);
    return {static_cast<std::int8_t>(k[0]), static_cast<std::int8_t>(k[1]),
            static_cast<std::int8_t>(k[2])};
}
} // namespace copy_image_detail

/// a + b per axis; throws core::Error beyond +-kMaxImage.
[[nodiscard]] inline CopyImage addImages(CopyImage const& a, CopyImage const& b) {
    return copy_image_detail::checked({a[0] + b[0], a[1] + b[1], a[2] + b[2]});
}
/// -k per axis.
[[nodiscard]] inline CopyImage negated(CopyImage const& k) {
    return {static_cast<std::int8_t>(-k[0]), static_cast<std::int8_t>(-k[1]),
            static_cast<std::int8_t>(-k[2])};
}
/// a - b per axis; throws core::Error beyond +-kMaxImage.
[[nodiscard]] inline CopyImage subtractImages(CopyImage const& a, CopyImage const& b) {
    return copy_image_detail::checked({a[0] - b[0], a[1] - b[1], a[2] - b[2]});
}
/// The image of a copy made through a block link with periodic image `linkImage` (see
/// domain::BlockLink: shift = -image * extent) from a copy with image `from`.
[[nodiscard]] inline CopyImage imageThroughLink(CopyImage const& from,
                                                std::array<int, 3> const& linkImage) {
    // x in the sender's frame is x + shift = x - linkImage * extent in the neighbour's frame.
    return copy_image_detail::checked(
        {from[0] - linkImage[0], from[1] - linkImage[1], from[2] - linkImage[2]});
}

/// Key of one copy in a block: a uid may be held several times at different images.
struct CopyKey {
    Uid uid = kInvalidUid;
    CopyImage image = kNoImage;
    friend bool operator==(CopyKey const& a, CopyKey const& b) {
        return a.uid == b.uid && sameImage(a.image, b.image);
    }
    friend auto operator<=>(CopyKey const&, CopyKey const&) = default;
};

struct CopyKeyHash {
    std::size_t operator()(CopyKey const& k) const noexcept {
        auto const packed =
            static_cast<std::uint64_t>(static_cast<std::uint8_t>(k.image[0])) |
            (static_cast<std::uint64_t>(static_cast<std::uint8_t>(k.image[1])) << 8U) |
            (static_cast<std::uint64_t>(static_cast<std::uint8_t>(k.image[2])) << 16U);
        return std::hash<std::uint64_t>{}(k.uid ^ (packed * 0x9E3779B97F4A7C15ULL));
    }
};

} // namespace regolith::particles
