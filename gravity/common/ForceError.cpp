#include "gravity/common/ForceError.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace regolith::gravity {

std::vector<double> relativeErrors(AccelView approx, AccelView reference) {
    std::vector<double> e(reference.ax.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
        double const dx = approx.ax[i] - reference.ax[i];
        double const dy = approx.ay[i] - reference.ay[i];
        double const dz = approx.az[i] - reference.az[i];
        double const ref =
            std::sqrt(reference.ax[i] * reference.ax[i] + reference.ay[i] * reference.ay[i] +
                      reference.az[i] * reference.az[i]);
        double const diff = std::sqrt(dx * dx + dy * dy + dz * dz);
        e[i] = ref > 0.0 ? diff / ref : diff;
    }
    return e;
}

ErrorStats errorStats(core::Comm const& comm, std::span<double const> errors) {
    return summarizeErrors(comm.allGatherVarying(errors));
}

ErrorStats summarizeErrors(std::vector<double> all) {
    ErrorStats s;
    s.count = static_cast<long long>(all.size());
    if (all.empty())
        return s;
    std::sort(all.begin(), all.end());
    auto const at = [&](double q) {
        auto const k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(all.size())));
        return all[std::min(all.size() - 1, k == 0 ? 0 : k - 1)];
    };
    s.median = at(0.5);
    s.p99 = at(0.99);
    s.max = all.back();
    return s;
}

} // namespace regolith::gravity
