#pragma once
/// The pairwise Newtonian kernel of the direct sum (the paper's Eq. 2, with optional Plummer
/// softening), summed in double-double so that the result does not depend on the order in
/// which blocks of sources arrive (and hence on the number of ranks).
///
/// Why double-double: each term is added with Knuth's TwoSum, the rounding error kept in a
/// second word. hi + lo then equals the exact sum to about 1e-32 relative to the largest
/// partial sum, so rounding it to one double gives the same bits for any summation order
/// unless the sum cancels to the size of that error (a grain at the centre of a symmetric pile)
/// or lies at a near-tie. Every term itself is computed from the same operands on every rank
/// (no FMA contraction on the x86-64 baseline target), so forces agree across rank counts to
/// far below 1e-12 always, and bitwise where reproducible mode fixes the order (DirectSum.hpp).
#include <cmath>
#include <cstddef>

namespace regolith::gravity::direct {

/// Adds b to the double-double (hi, lo): Knuth's TwoSum, exact error term. Must not be
/// compiled with -ffast-math (the error term would be optimised away).
inline void twoSumAdd(double& hi, double& lo, double b) {
    double const s = hi + b;
    double const bb = s - hi;
    double const err = (hi - (s - bb)) + (b - bb);
    hi = s;
    lo += err;
}

/// Per-target double-double accumulators for ax, ay, az, phi (8 arrays of `n`).
struct DoubleDoubleField {
    double* hx;
    double* lx;
    double* hy;
    double* ly;
    double* hz;
    double* lz;
    double* hp;
    double* lp;
};

/// Adds to targets [0, nt) (positions tx, ty, tz) the field of sources [0, ns): acceleration
/// G m (x_s - x_t) / (r² + ε²)^{3/2} and potential -G m / (r² + ε²)^{1/2}. A pair at zero
/// separation (a grain and itself) contributes nothing. `eps2` = ε² in m². The inner loop
/// runs over targets, so it vectorises without reassociating any sum.
inline void accumulateDirectTile(double const* tx, double const* ty, double const* tz,
                                 std::size_t nt, double const* sx, double const* sy,
                                 double const* sz, double const* sm, std::size_t ns, double G,
                                 double eps2, DoubleDoubleField acc) {
    for (std::size_t j = 0; j < ns; ++j) {
        double const xj = sx[j];
        double const yj = sy[j];
        double const zj = sz[j];
        double const gm = G * sm[j];
#pragma omp simd
        for (std::size_t i = 0; i < nt; ++i) {
            double const dx = xj - tx[i];
            double const dy = yj - ty[i];
            double const dz = zj - tz[i];
            double const r2 = dx * dx + dy * dy + dz * dz;
            bool const valid = r2 > 0.0;
            // Branch-free (vectorisable): always divide, then select.
            double const invAll = 1.0 / std::sqrt(valid ? r2 + eps2 : 1.0);
            double const inv = valid ? invAll : 0.0;
            double const f = gm * (inv * inv * inv);
            twoSumAdd(acc.hx[i], acc.lx[i], f * dx);
            twoSumAdd(acc.hy[i], acc.ly[i], f * dy);
            twoSumAdd(acc.hz[i], acc.lz[i], f * dz);
            twoSumAdd(acc.hp[i], acc.lp[i], -gm * inv);
        }
    }
}

} // namespace regolith::gravity::direct
