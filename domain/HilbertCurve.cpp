#include "domain/HilbertCurve.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <bit>
#include <string>

namespace regolith::domain {

namespace {

constexpr int kDims = 3;
using Coords = std::array<std::uint32_t, 3>;

void checkBits(int bits) {
    if (bits < 0 || bits > kMaxHilbertBits)
        throw core::Error("Hilbert curve: grid exponent " + std::to_string(bits) + " not in [0, " +
                          std::to_string(kMaxHilbertBits) + "]");
}

/// Skilling (2004), AxestoTranspose: turns axis coordinates into the "transposed" Hilbert
/// index, whose bit j of X[i] is bit (kDims * j + kDims - 1 - i) of the index.
void axesToTranspose(Coords& x, int bits) {
    std::uint32_t const m = std::uint32_t{1} << (bits - 1);
    // Inverse undo.
    for (std::uint32_t q = m; q > 1; q >>= 1) {
        std::uint32_t const p = q - 1;
        for (int i = 0; i < kDims; ++i) {
            if (x[i] & q) {
                x[0] ^= p; // invert
            } else {
                std::uint32_t const t = (x[0] ^ x[i]) & p; // exchange
                x[0] ^= t;
                x[i] ^= t;
            }
        }
    }
    // Gray encode.
    for (int i = 1; i < kDims; ++i)
        x[i] ^= x[i - 1];
    std::uint32_t t = 0;
    for (std::uint32_t q = m; q > 1; q >>= 1)
        if (x[kDims - 1] & q)
            t ^= q - 1;
    for (int i = 0; i < kDims; ++i)
        x[i] ^= t;
}

/// Skilling (2004), TransposetoAxes: the inverse of axesToTranspose.
void transposeToAxes(Coords& x, int bits) {
    std::uint32_t const n = std::uint32_t{2} << (bits - 1);
    // Gray decode by H ^ (H / 2).
    std::uint32_t t = x[kDims - 1] >> 1;
    for (int i = kDims - 1; i > 0; --i)
        x[i] ^= x[i - 1];
    x[0] ^= t;
    // Undo excess work.
    for (std::uint32_t q = 2; q != n; q <<= 1) {
        std::uint32_t const p = q - 1;
        for (int i = kDims - 1; i >= 0; --i) {
            if (x[i] & q) {
                x[0] ^= p;
            } else {
                t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
    }
}

} // namespace

std::uint64_t hilbertIndex(std::array<std::uint32_t, 3> cell, int bits) {
    checkBits(bits);
    if (bits == 0)
        return 0;
    axesToTranspose(cell, bits);
    std::uint64_t index = 0;
    for (int j = bits - 1; j >= 0; --j)
        for (int i = 0; i < kDims; ++i)
            index = (index << 1) | ((cell[i] >> j) & 1U);
    return index;
}

std::array<std::uint32_t, 3> hilbertCell(std::uint64_t index, int bits) {
    checkBits(bits);
    Coords x{0, 0, 0};
    if (bits == 0)
        return x;
    for (int j = bits - 1; j >= 0; --j)
        for (int i = 0; i < kDims; ++i) {
            int const bit = kDims * j + (kDims - 1 - i);
            x[i] |= static_cast<std::uint32_t>((index >> bit) & 1U) << j;
        }
    transposeToAxes(x, bits);
    return x;
}

int hilbertBitsFor(std::array<int, 3> extent) {
    int bits = 0;
    for (int const n : extent)
        bits = std::max(bits, static_cast<int>(std::bit_width(static_cast<unsigned>(n - 1))));
    return bits;
}

} // namespace regolith::domain
