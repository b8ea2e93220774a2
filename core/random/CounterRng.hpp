#pragma once
/// Counter-based random numbers keyed by (seed, particle uid): the numbers a particle draws
/// depend only on the seed, its uid and how many it drew, never on ranks or blocks, which is
/// what the reproducible mode (docs/design.md, "Reproducible mode") needs.
#include "core/random/Philox.hpp"

#include <cstdint>
#include <limits>

namespace regolith::core::random {

/// A stream of Philox4x32-10 blocks. Mapping (fixed; tests pin it):
///   key     = {seed bits 0-31, seed bits 32-63}
///   counter = {block index, stream, uid bits 0-31, uid bits 32-63}
/// Block b yields 4 words; next() takes two consecutive words w[2i] | w[2i+1] << 32, so block b
/// gives next() values 2b and 2b+1. A (seed, uid, stream) triple has 2^32 blocks (2^33 64-bit
/// values); drawing beyond throws core::Error. Different uids or streams give disjoint counter
/// ranges, i.e. independent streams (Salmon et al. 2011). `stream` lets one particle
/// draw fresh numbers per purpose or per time step. Satisfies UniformRandomBitGenerator.
class CounterRng {
public:
    using result_type = std::uint64_t;

    explicit CounterRng(std::uint64_t seed, std::uint64_t uid, std::uint32_t stream = 0)
        : m_key{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}
        , m_counter{0, stream, static_cast<std::uint32_t>(uid),
                    static_cast<std::uint32_t>(uid >> 32)} {}

    /// 64 uniformly distributed bits.
    std::uint64_t next() {
        if (m_used == 4)
            refill();
        std::uint64_t const lo = m_block[m_used];
        std::uint64_t const hi = m_block[m_used + 1];
        m_used += 2;
        return lo | (hi << 32);
    }
    result_type operator()() { return next(); }
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

    /// Uniform in [0, 1): the top 53 bits of next() times 2^-53 (every value a multiple of
    /// 2^-53, so 1 is never returned).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    /// Uniform in [a, b). Pre: a < b, both finite.
    double uniform(double a, double b);
    /// Standard normal (mean 0, variance 1) by the Box–Muller transform (Box & Muller 1958),
    /// one pair per two uniforms; the second value of a pair is returned by the next call.
    double normal();
    /// Normal with `mean` and standard deviation `sigma`.
    double normal(double mean, double sigma) { return mean + sigma * normal(); }

    /// Number of Philox blocks generated so far.
    [[nodiscard]] std::uint64_t blocksUsed() const { return m_blocks; }

private:
    void refill();

    PhiloxKey m_key;
    PhiloxCounter m_counter;
    PhiloxCounter m_block{};
    unsigned m_used = 4; ///< words of m_block consumed
    std::uint64_t m_blocks = 0;
    double m_spare = 0.0;
    bool m_hasSpare = false;
};

} // namespace regolith::core::random
