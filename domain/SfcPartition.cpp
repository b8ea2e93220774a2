#include "domain/SfcPartition.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace regolith::domain {

namespace {

/// Sums of the weights over index ranges [s, e), from prefix sums: every range's load is
/// computed the same way, so comparisons against a load taken from it are exact.
class PrefixLoads {
public:
    explicit PrefixLoads(std::span<double const> weights)
        : m_prefix(weights.size() + 1, 0.0) {
        for (std::size_t i = 0; i < weights.size(); ++i)
            m_prefix[i + 1] = m_prefix[i] + weights[i];
    }
    [[nodiscard]] std::size_t size() const { return m_prefix.size() - 1; }
    [[nodiscard]] double load(std::size_t s, std::size_t e) const {
        return m_prefix[e] - m_prefix[s];
    }
    /// The largest e >= s with load(s, e) <= bound (the load grows with e).
    [[nodiscard]] std::size_t reach(std::size_t s, double bound) const {
        std::size_t lo = s, hi = size(); // load(s, lo) <= bound holds for lo = s
        while (lo < hi) {
            std::size_t const mid = hi - (hi - lo) / 2;
            if (load(s, mid) <= bound)
                lo = mid;
            else
                hi = mid - 1;
        }
        return lo;
    }
    /// The largest load of the cut of [0, size()) into at most `parts` contiguous pieces, each
    /// as long as `bound` allows (the greedy probe), or infinity if they do not reach the end.
    [[nodiscard]] double probe(std::size_t parts, double bound) const {
        double largest = 0.0;
        std::size_t s = 0;
        for (std::size_t k = 0; k < parts && s < size(); ++k) {
            std::size_t const e = reach(s, bound);
            largest = std::max(largest, load(s, e));
            s = e;
        }
        return s == size() ? largest : std::numeric_limits<double>::infinity();
    }

private:
    std::vector<double> m_prefix;
};

/// The least largest load of any cut of the sequence into `parts` contiguous pieces
/// (chains-on-chains partitioning), by bisection on that load with the greedy probe (Pinar &
/// Aykanat, "Fast optimal load balancing algorithms for 1D partitioning", J. Parallel Distrib.
/// Comput. 64, 2004): it lies between the larger of the mean and the heaviest element, and
/// `reached`, the largest load of a known cut; a bound that fits lowers the upper end to the
/// largest load its cut reaches, one that does not raises the lower end. The ends meet at the
/// least largest load within a few dozen probes of O(parts log n) each.
double leastBottleneck(PrefixLoads const& loads, std::span<double const> weights, int parts,
                       double reached) {
    auto const P = static_cast<std::size_t>(parts);
    double lo = loads.load(0, loads.size()) / static_cast<double>(parts);
    for (double const w : weights)
        lo = std::max(lo, w);
    double hi = reached;
    if (loads.probe(P, lo) <= lo) // the lower bound is reached
        return lo;
    // lo never fits, hi always does; each probe halves the interval at least.
    for (int k = 0; k < 200 && lo < hi; ++k) {
        double const mid = lo + 0.5 * (hi - lo);
        if (!(mid > lo && mid < hi))
            break;
        double const largest = loads.probe(P, mid);
        if (largest <= mid)
            hi = largest;
        else
            lo = mid;
    }
    return hi;
}

/// The start of every part of a contiguous `owner` (part r: [begin[r], begin[r + 1])).
std::vector<std::size_t> beginsOf(std::vector<int> const& owner, int parts) {
    auto const P = static_cast<std::size_t>(parts);
    std::vector<std::size_t> begin(P + 1, owner.size());
    std::size_t i = 0;
    for (std::size_t r = 0; r < P; ++r) { // the first element of owner >= r
        while (i < owner.size() && static_cast<std::size_t>(owner[i]) < r)
            ++i;
        begin[r] = i;
    }
    return begin;
}

/// Cuts whose largest load is at most `bound` (which some cut reaches), each as near as the
/// bound allows to the cut of `wanted`: cut r lies between the earliest start from which the
/// parts after it fit and the farthest the part before it reaches. Where `wanted` already
/// keeps to the bound it is returned unchanged.
std::vector<std::size_t> cutsNear(PrefixLoads const& loads, double bound,
                                  std::vector<std::size_t> const& wanted) {
    if (wanted.size() < 3) // one part: nothing to cut
        return wanted;
    std::size_t const P = wanted.size() - 1;
    std::size_t const n = loads.size();
    std::vector<std::size_t> earliest(P + 1, n); // from the end: part r may start here
    for (std::size_t r = P - 1; r > 0; --r) {
        std::size_t s = earliest[r + 1];
        while (s > 0 && loads.load(s - 1, earliest[r + 1]) <= bound)
            --s;
        earliest[r] = s;
    }
    std::vector<std::size_t> cut = wanted; // cut[0] = 0 and cut[P] = n stay
    for (std::size_t r = 1; r < P; ++r) {
        std::size_t const lo = std::max(earliest[r], cut[r - 1]);
        std::size_t const hi = std::max(lo, loads.reach(cut[r - 1], bound));
        cut[r] = std::clamp(wanted[r], lo, hi);
    }
    return cut;
}

/// Moves single elements across the cuts `begin` while that relieves a part: the boundary
/// element of the heavier of two neighbouring parts goes to the lighter one when the lighter
/// then still weighs less than the heavier did. Each move lowers the sum of squared loads, and
/// neither raises the largest load nor lowers the smallest; the moves stop where no single
/// element can move (a local optimum of the cut).
void relieveHeaviest(std::span<double const> weights, std::vector<std::size_t>& begin) {
    std::size_t const P = begin.size() - 1;
    std::vector<double> load(P, 0.0);
    for (std::size_t r = 0; r < P; ++r)
        for (std::size_t k = begin[r]; k < begin[r + 1]; ++k)
            load[r] += weights[k];
    // Each pass visits every cut; a bound on the passes keeps rounding from cycling.
    for (std::size_t pass = 0; pass < 4 * weights.size() + 4; ++pass) {
        bool moved = false;
        for (std::size_t r = 0; r + 1 < P; ++r) {
            std::size_t const cut = begin[r + 1]; // between parts r and r + 1
            if (load[r] > load[r + 1] && cut > begin[r]) {
                double const w = weights[cut - 1];
                if (w > 0.0 && load[r + 1] + w < load[r]) {
                    load[r] -= w;
                    load[r + 1] += w;
                    begin[r + 1] = cut - 1;
                    moved = true;
                }
            } else if (load[r + 1] > load[r] && cut < begin[r + 2]) {
                double const w = weights[cut];
                if (w > 0.0 && load[r] + w < load[r + 1]) {
                    load[r + 1] -= w;
                    load[r] += w;
                    begin[r + 1] = cut + 1;
                    moved = true;
                }
            }
        }
        if (!moved)
            break;
    }
}

} // namespace

std::vector<int> partitionCurve(std::span<double const> weights, int parts) {
    if (parts < 1)
        throw core::InputError(
            fmt::format("block partition: expected at least one rank, got {}", parts));
    double total = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        double const w = weights[i];
        if (!std::isfinite(w) || w < 0.0)
            throw core::InputError(fmt::format(
                "block weights: block {} along the curve has weight {} (expected finite and >= 0)",
                i, w));
        total += w;
    }
    bool const counted = total <= 0.0;
    if (counted)
        total = static_cast<double>(weights.size());

    std::vector<int> owner(weights.size(), 0);
    double const p = static_cast<double>(parts);
    double prefix = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        double const w = counted ? 1.0 : weights[i];
        double const mid = prefix + 0.5 * w;
        auto const r = static_cast<int>(std::floor(mid / total * p));
        owner[i] = std::clamp(r, 0, parts - 1);
        // Rounding must never send a later element to an earlier rank.
        if (i > 0)
            owner[i] = std::max(owner[i], owner[i - 1]);
        prefix += w;
    }
    if (counted)
        return owner;
    PrefixLoads const loads(weights);
    std::vector<std::size_t> begin = beginsOf(owner, parts);
    double reached = 0.0; // the midpoint cut's largest load
    for (std::size_t r = 0; r + 1 < begin.size(); ++r)
        reached = std::max(reached, loads.load(begin[r], begin[r + 1]));
    begin = cutsNear(loads, leastBottleneck(loads, weights, parts, reached), begin);
    relieveHeaviest(weights, begin);
    for (std::size_t r = 0; r + 1 < begin.size(); ++r)
        for (std::size_t k = begin[r]; k < begin[r + 1]; ++k)
            owner[k] = static_cast<int>(r);
    return owner;
}

} // namespace regolith::domain
