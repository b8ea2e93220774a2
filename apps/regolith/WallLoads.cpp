#include "apps/regolith/WallLoads.hpp"

#include <span>

namespace regolith::apps {

std::vector<RunSummary::Wall> reduceWallLoads(core::Comm const& comm,
                                              particles::WallList const& walls) {
    constexpr std::size_t kValues = 7; // force, torque, work
    std::vector<double> values(kValues * walls.size());
    for (std::size_t k = 0; k < walls.size(); ++k) {
        particles::WallLoad const& l = walls.load(k);
        double* v = values.data() + kValues * k;
        for (int d = 0; d < 3; ++d) {
            v[d] = l.force[d];
            v[3 + d] = l.torque[d];
        }
        v[6] = walls.work(k);
    }
    if (!values.empty())
        comm.allReduceInPlace(std::span<double>(values), core::ReduceOp::Sum);
    std::vector<RunSummary::Wall> out(walls.size());
    for (std::size_t k = 0; k < walls.size(); ++k) {
        double const* v = values.data() + kValues * k;
        out[k].force = core::Vec3(v[0], v[1], v[2]);
        out[k].torque = core::Vec3(v[3], v[4], v[5]);
        out[k].work = v[6];
    }
    return out;
}

} // namespace regolith::apps
