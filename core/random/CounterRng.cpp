#include "core/random/CounterRng.hpp"

#include "core/Error.hpp"

#include <cmath>
#include <numbers>

namespace regolith::core::random {

void CounterRng::refill() {
    if (m_blocks > std::numeric_limits<std::uint32_t>::max())
        throw Error("CounterRng: stream exhausted (2^32 blocks drawn for one (seed, uid, stream))");
    m_counter[0] = static_cast<std::uint32_t>(m_blocks);
    m_block = philox4x32(m_counter, m_key);
    ++m_blocks;
    m_used = 0;
}

double CounterRng::uniform(double a, double b) {
    double const x = a + (b - a) * uniform();
    // Rounding of a + (b - a) * u can reach b; keep the interval half-open.
    return x < b ? x : std::nextafter(b, a);
}

double CounterRng::normal() {
    if (m_hasSpare) {
        m_hasSpare = false;
        return m_spare;
    }
    double const u1 = 1.0 - uniform(); // (0, 1]: log is finite
    double const u2 = uniform();
    double const r = std::sqrt(-2.0 * std::log(u1));
    double const theta = 2.0 * std::numbers::pi * u2;
    m_spare = r * std::sin(theta);
    m_hasSpare = true;
    return r * std::cos(theta);
}

} // namespace regolith::core::random
