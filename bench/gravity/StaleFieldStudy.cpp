#include "bench/gravity/StaleFieldStudy.hpp"

#include "gravity/direct/DirectSum.hpp"
#include "gravity/update/UpdatePolicy.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

namespace regolith::bench {

namespace gs = gravity::samples;

StaleFieldStudy::StaleFieldStudy(gs::Body const& grains, std::span<std::size_t const> sample,
                                 unsigned seed)
    : m_grains(&grains)
    , m_sample(sample)
    , m_ux(grains.size())
    , m_uy(grains.size())
    , m_uz(grains.size()) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> speed(0.0, 1.0);
    for (std::size_t i = 0; i < grains.size(); ++i) {
        double x = 0.0, y = 0.0, z = 0.0, len = 0.0;
        while (len < 1e-6) {
            x = normal(rng);
            y = normal(rng);
            z = normal(rng);
            len = std::sqrt(x * x + y * y + z * z);
        }
        double const s = speed(rng) / len;
        m_ux[i] = s * x;
        m_uy[i] = s * y;
        m_uz[i] = s * z;
    }
}

StalePoint StaleFieldStudy::point(core::Comm const& comm, double threshold, double stepDisplacement,
                                  gravity::AccelView stale, double evalWall, double evalCpu) const {
    gs::Body const& g = *m_grains;
    std::size_t const n = g.size();
    // Scale so that the fastest grain has moved exactly `threshold`.
    double fastest = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        fastest =
            std::max(fastest, std::sqrt(m_ux[i] * m_ux[i] + m_uy[i] * m_uy[i] + m_uz[i] * m_uz[i]));
    double const scale = fastest > 0.0 ? threshold / fastest : 0.0;
    gs::Body moved = g;
    for (std::size_t i = 0; i < n; ++i) {
        moved.x[i] += scale * m_ux[i];
        moved.y[i] += scale * m_uy[i];
        moved.z[i] += scale * m_uz[i];
    }

    // The policy's check, as the app does it every step between updates.
    std::vector<std::uint64_t> uid(n);
    for (std::size_t i = 0; i < n; ++i)
        uid[i] = i;
    gravity::UpdatePolicy policy(threshold);
    policy.markUpdated(uid, g.x, g.y, g.z);
    double dueSeconds = 1e300;
    for (int repeat = 0; repeat < 3; ++repeat) {
        double const t0 = MPI_Wtime();
        bool const due = policy.due(comm, uid, moved.x, moved.y, moved.z);
        dueSeconds = std::min(dueSeconds, MPI_Wtime() - t0);
        (void)due;
    }

    // Exact field at the moved sample, and the stale field kept there.
    gs::Body sample;
    std::vector<double> ax, ay, az;
    for (std::size_t k : m_sample) {
        sample.push(moved, k);
        ax.push_back(stale.ax[k]);
        ay.push_back(stale.ay[k]);
        az.push_back(stale.az[k]);
    }
    std::vector<double> rx(sample.size()), ry(sample.size()), rz(sample.size());
    gravity::direct::directSumSerial(sample.view(), moved.view(), {rx, ry, rz}, {});

    StalePoint p;
    p.threshold = threshold;
    p.stepsPerUpdate = std::max(1.0, threshold / stepDisplacement);
    p.dueSeconds = comm.allReduce(dueSeconds, core::ReduceOp::Max);
    p.wallSeconds = p.dueSeconds + evalWall / p.stepsPerUpdate;
    p.cpuSeconds = p.dueSeconds + evalCpu / p.stepsPerUpdate;
    p.error = gravity::errorStats(comm, gravity::relativeErrors({ax, ay, az}, {rx, ry, rz}));
    return p;
}

} // namespace regolith::bench
