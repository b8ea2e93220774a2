#include "gravity/direct/DirectSum.hpp"

#include "core/Error.hpp"
#include "core/mpi/Requests.hpp"
#include "core/mpi/Tags.hpp"
#include "gravity/common/SimdClones.hpp"
#include "gravity/direct/DirectKernel.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>

namespace regolith::gravity::direct {

namespace {

/// Targets are processed in tiles so that their accumulators stay in the L1 cache while a
/// whole block of sources streams past.
constexpr std::size_t kTargetTile = 256;

/// Double-double accumulators of all targets, 8 arrays of n.
class Accumulators {
public:
    explicit Accumulators(std::size_t n)
        : m_data(8 * n, 0.0)
        , m_n(n) {}

    [[nodiscard]] DoubleDoubleField at(std::size_t offset) {
        double* p = m_data.data();
        return {p + offset,           p + m_n + offset,     p + 2 * m_n + offset,
                p + 3 * m_n + offset, p + 4 * m_n + offset, p + 5 * m_n + offset,
                p + 6 * m_n + offset, p + 7 * m_n + offset};
    }

    /// Writes hi + lo into `out`; returns ½ Σ m φ.
    double finish(FieldOut out, std::span<double const> mass) {
        DoubleDoubleField const a = at(0);
        double energy = 0.0;
        for (std::size_t i = 0; i < m_n; ++i) {
            out.ax[i] = a.hx[i] + a.lx[i];
            out.ay[i] = a.hy[i] + a.ly[i];
            out.az[i] = a.hz[i] + a.lz[i];
            double const phi = a.hp[i] + a.lp[i];
            if (!out.phi.empty())
                out.phi[i] = phi;
            energy += 0.5 * mass[i] * phi;
        }
        return energy;
    }

private:
    std::vector<double> m_data;
    std::size_t m_n;
};

/// Adds the field of sources (SoA pointers, ns grains) to every target. This file is
/// compiled without FMA contraction, so both clones make the same IEEE operations.
REGOLITH_SIMD_CLONES
void accumulateAll(PointMasses const& targets, double const* sx, double const* sy, double const* sz,
                   double const* sm, std::size_t ns, DirectOptions const& options,
                   Accumulators& acc) {
    double const eps2 = options.softening * options.softening;
    std::size_t const nt = targets.size();
    for (std::size_t t0 = 0; t0 < nt; t0 += kTargetTile) {
        std::size_t const len = std::min(kTargetTile, nt - t0);
        accumulateDirectTile(targets.x.data() + t0, targets.y.data() + t0, targets.z.data() + t0,
                             len, sx, sy, sz, sm, ns, options.G, eps2, acc.at(t0));
    }
}

/// Adds every rank's grains to `acc` as they pass around the ring.
void ringPass(core::Comm const& comm, PointMasses const& local, DirectOptions const& options,
              Accumulators& acc) {
    int const p = comm.size();
    int const rank = comm.rank();
    std::vector<long long> const counts = comm.allGather(static_cast<long long>(local.size()));
    long long const maxCount = *std::max_element(counts.begin(), counts.end());
    if (4 * maxCount > INT_MAX)
        throw core::Error("gravity direct sum: a block of grains exceeds the MPI count limit");

    // A block is x..., y..., z..., m... of one rank's grains.
    auto const capacity = static_cast<std::size_t>(4 * maxCount);
    std::vector<double> current(capacity);
    std::vector<double> next(capacity);
    std::size_t const n = local.size();
    std::copy(local.x.begin(), local.x.end(), current.begin());
    std::copy(local.y.begin(), local.y.end(), current.begin() + static_cast<long>(n));
    std::copy(local.z.begin(), local.z.end(), current.begin() + static_cast<long>(2 * n));
    std::copy(local.m.begin(), local.m.end(), current.begin() + static_cast<long>(3 * n));

    int const right = (rank + 1) % p;
    int const left = (rank + p - 1) % p;
    int const tag = core::toInt(core::Tag::DirectGravityRing);
    for (int step = 0; step < p; ++step) {
        // At step k this rank holds the block of rank (rank - k) mod p.
        auto const owner = static_cast<std::size_t>((rank - step + p) % p);
        auto const ns = static_cast<std::size_t>(counts[owner]);
        std::array<MPI_Request, 2> requests{MPI_REQUEST_NULL, MPI_REQUEST_NULL};
        if (step + 1 < p) {
            auto const incoming = static_cast<std::size_t>((rank - step - 1 + 2 * p) % p);
            core::Comm::check(MPI_Irecv(next.data(), static_cast<int>(4 * counts[incoming]),
                                        MPI_DOUBLE, left, tag, comm.raw(), &requests[0]),
                              "MPI_Irecv (direct gravity ring)");
            core::Comm::check(MPI_Isend(current.data(), static_cast<int>(4 * ns), MPI_DOUBLE, right,
                                        tag, comm.raw(), &requests[1]),
                              "MPI_Isend (direct gravity ring)");
        }
        double const* block = current.data();
        accumulateAll(local, block, block + ns, block + 2 * ns, block + 3 * ns, ns, options, acc);
        if (step + 1 < p) {
            core::Comm::check(MPI_Waitall(2, requests.data(), MPI_STATUSES_IGNORE),
                              "MPI_Waitall (direct gravity ring)");
            std::swap(current, next);
        }
    }
}

/// Adds every rank's grains to `acc` in one order on any number of ranks: by the bits of
/// (x, y, z, m). Grains alike in all four add the same terms, so their order is immaterial.
void canonicalPass(core::Comm const& comm, PointMasses const& local, DirectOptions const& options,
                   Accumulators& acc) {
    std::size_t const n = local.size();
    std::vector<double> mine(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        mine[4 * i] = local.x[i];
        mine[4 * i + 1] = local.y[i];
        mine[4 * i + 2] = local.z[i];
        mine[4 * i + 3] = local.m[i];
    }
    std::vector<double> const all = comm.allGatherVarying<double>(std::span<double const>(mine));
    std::size_t const ns = all.size() / 4;
    using Key = std::array<std::uint64_t, 4>;
    std::vector<std::pair<Key, std::size_t>> order(ns);
    for (std::size_t j = 0; j < ns; ++j) {
        for (std::size_t c = 0; c < 4; ++c)
            order[j].first[c] = std::bit_cast<std::uint64_t>(all[4 * j + c]);
        order[j].second = j;
    }
    std::sort(order.begin(), order.end());
    std::vector<double> sources(4 * ns); // x..., y..., z..., m...
    for (std::size_t k = 0; k < ns; ++k)
        for (std::size_t c = 0; c < 4; ++c)
            sources[c * ns + k] = all[4 * order[k].second + c];
    double const* s = sources.data();
    accumulateAll(local, s, s + ns, s + 2 * ns, s + 3 * ns, ns, options, acc);
}

} // namespace

void validate(DirectOptions const& options) {
    if (!(options.G > 0.0) || !std::isfinite(options.G))
        throw core::InputError(
            fmt::format("gravity.G = {}: Newton's constant must be finite and > 0", options.G));
    if (!(options.softening >= 0.0) || !std::isfinite(options.softening))
        throw core::InputError(
            fmt::format("gravity.softening = {}: the softening length must be finite and >= 0 m",
                        options.softening));
}

double directSumSerial(PointMasses const& targets, PointMasses const& sources, FieldOut out,
                       DirectOptions const& options) {
    validateFieldOut(out, targets.size());
    Accumulators acc(targets.size());
    accumulateAll(targets, sources.x.data(), sources.y.data(), sources.z.data(), sources.m.data(),
                  sources.size(), options, acc);
    return acc.finish(out, targets.m);
}

DirectSum::DirectSum(core::Comm const& comm, DirectOptions const& options)
    : m_comm(comm.duplicate())
    , m_options(options) {
    validate(m_options);
}

double DirectSum::evaluate(PointMasses const& local, FieldOut out) {
    validatePointMassesCollective(m_comm, local, "gravity");
    validateFieldOut(out, local.size());
    Accumulators acc(local.size());
    if (m_options.reproducible)
        canonicalPass(m_comm, local, m_options, acc);
    else
        ringPass(m_comm, local, m_options, acc);
    double const energy = acc.finish(out, local.m);
    return m_comm.allReduce(energy, core::ReduceOp::Sum);
}

} // namespace regolith::gravity::direct
