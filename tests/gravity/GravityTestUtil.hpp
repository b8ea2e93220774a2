#pragma once
// Helpers shared by the tree and direct gravity tests: a body split into x-slabs, one per
// rank, and the reference field from the serial direct sum over the whole body.
#include "core/mpi/Comm.hpp"
#include "gravity/common/ForceError.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/direct/DirectSum.hpp"
#include "gravity/samples/SyntheticBodies.hpp"

#include <cmath>
#include <vector>

namespace regolith::testing {

/// MPI_COMM_WORLD as a core::Comm, for the gravity tests.
inline core::Comm const& world() {
    static core::Comm const comm(MPI_COMM_WORLD);
    return comm;
}

/// Accelerations and potentials of n grains, owning.
struct Field {
    std::vector<double> ax, ay, az, phi;

    explicit Field(std::size_t n)
        : ax(n)
        , ay(n)
        , az(n)
        , phi(n) {}

    [[nodiscard]] gravity::FieldOut out() { return {ax, ay, az, phi}; }
    [[nodiscard]] gravity::AccelView view() const { return {ax, ay, az}; }
};

/// This rank's slab of `body` (equal-count slabs along x).
inline gravity::samples::Body localSlab(core::Comm const& comm,
                                        gravity::samples::Body const& body) {
    return gravity::samples::slabOf(body, comm.rank(), comm.size());
}

/// The exact field at the grains of `local` due to all of `body` (serial direct sum).
inline Field referenceField(gravity::samples::Body const& local, gravity::samples::Body const& body,
                            double G, double softening = 0.0) {
    Field f(local.size());
    gravity::direct::directSumSerial(local.view(), body.view(), f.out(), {G, softening});
    return f;
}

/// |Σ m a| / Σ m |a| over all ranks: the total force relative to its scale. COLLECTIVE.
inline double relativeTotalForce(core::Comm const& comm, std::vector<double> const& m,
                                 Field const& f) {
    std::vector<double> s(4, 0.0);
    for (std::size_t i = 0; i < m.size(); ++i) {
        s[0] += m[i] * f.ax[i];
        s[1] += m[i] * f.ay[i];
        s[2] += m[i] * f.az[i];
        s[3] += m[i] * std::sqrt(f.ax[i] * f.ax[i] + f.ay[i] * f.ay[i] + f.az[i] * f.az[i]);
    }
    comm.allReduceInPlace(std::span<double>(s), core::ReduceOp::Sum);
    return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / s[3];
}

/// The paper-like agglomerate used by the tests (radii 20–60 m, 3000 kg/m³).
inline gravity::samples::Body testAgglomerate(std::size_t n, std::uint64_t seed = 7) {
    return gravity::samples::packedAgglomerate(n, 20.0, 60.0, 3000.0, 0.3, core::Vec3::Zero(),
                                               seed);
}

} // namespace regolith::testing
