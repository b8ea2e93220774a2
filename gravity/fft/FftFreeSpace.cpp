#include "gravity/fft/FftFreeSpace.hpp"

#include "core/Error.hpp"

#include <mpi.h>

#include <cmath>
#include <fftw3.h>
#include <numeric>
#include <vector>

namespace regolith::gravity {

namespace {

/// ∫ over the unit cube centred at 0 of 1/|r| dV: the potential at the centre of a uniform
/// cube of side a and density ρ is -G ρ a² times this (the Green's function's self term).
constexpr double kCubeSelf = 2.3800772;

} // namespace

struct FftFreeSpace::Fftw {
    std::array<std::int64_t, 3> n{}; ///< grid cells per axis
    std::array<int, 3> p{};          ///< padded: 2n
    std::size_t realSize = 0;
    std::size_t complexSize = 0;
    double* real = nullptr;
    fftw_complex* spectrum = nullptr;
    fftw_complex* green = nullptr;
    fftw_plan forward = nullptr;
    fftw_plan backward = nullptr;
    std::vector<std::int64_t> cellOfRow; ///< global row -> linear index in the padded grid

    Fftw() = default;
    Fftw(Fftw const&) = delete;
    Fftw& operator=(Fftw const&) = delete;
    ~Fftw() {
        if (forward)
            fftw_destroy_plan(forward);
        if (backward)
            fftw_destroy_plan(backward);
        fftw_free(real);
        fftw_free(spectrum);
        fftw_free(green);
    }
    [[nodiscard]] std::size_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
        return static_cast<std::size_t>(i + p[2] * (j + static_cast<std::int64_t>(p[1]) * k));
    }
};

FftFreeSpace::FftFreeSpace(core::Comm const& comm, CellLayout const& layout, double G)
    : m_comm(comm.duplicate())
    , m_layout(&layout) {
    auto const& periodic = layout.forest().periodic();
    if (periodic[0] || periodic[1] || periodic[2])
        throw core::InputError("gravity.poisson = \"fft\": the FFT free-space solver needs a "
                               "domain without periodic axes (domain.periodic)");
    if (m_comm.rank() != 0)
        return;
    double const t0 = MPI_Wtime();
    m_fftw = std::make_unique<Fftw>();
    auto& f = *m_fftw;
    auto const& N = layout.globalCells();
    // FFTW's last dimension varies fastest: (z, y, x) with x fastest, like our rows.
    f.n = {N[2], N[1], N[0]};
    f.p = {static_cast<int>(2 * N[2]), static_cast<int>(2 * N[1]), static_cast<int>(2 * N[0])};
    f.realSize = static_cast<std::size_t>(f.p[0]) * static_cast<std::size_t>(f.p[1]) *
                 static_cast<std::size_t>(f.p[2]);
    f.complexSize = static_cast<std::size_t>(f.p[0]) * static_cast<std::size_t>(f.p[1]) *
                    static_cast<std::size_t>(f.p[2] / 2 + 1);
    f.real = fftw_alloc_real(f.realSize);
    f.spectrum = fftw_alloc_complex(f.complexSize);
    f.green = fftw_alloc_complex(f.complexSize);
    if (!f.real || !f.spectrum || !f.green)
        throw core::Error("FftFreeSpace: out of memory for the padded grid");
    f.forward = fftw_plan_dft_r2c_3d(f.p[0], f.p[1], f.p[2], f.real, f.spectrum, FFTW_ESTIMATE);
    f.backward = fftw_plan_dft_c2r_3d(f.p[0], f.p[1], f.p[2], f.spectrum, f.real, FFTW_ESTIMATE);
    if (!f.forward || !f.backward)
        throw core::Error("FftFreeSpace: FFTW could not plan the transforms");

    // Green's function on the padded grid, offsets wrapped into [-n, n).
    core::Vec3 const h = layout.spacing();
    double const volume = layout.cellVolume();
    for (std::int64_t k = 0; k < f.p[0]; ++k)
        for (std::int64_t j = 0; j < f.p[1]; ++j)
            for (std::int64_t i = 0; i < f.p[2]; ++i) {
                double const dx = h[0] * static_cast<double>(i < N[0] ? i : i - f.p[2]);
                double const dy = h[1] * static_cast<double>(j < N[1] ? j : j - f.p[1]);
                double const dz = h[2] * static_cast<double>(k < N[2] ? k : k - f.p[0]);
                double const r = std::sqrt(dx * dx + dy * dy + dz * dz);
                f.real[f.index(i, j, k)] =
                    r > 0.0 ? -G * volume / r : -G * kCubeSelf * std::cbrt(volume * volume);
            }
    fftw_execute_dft_r2c(f.forward, f.real, f.green);
    double const scale = 1.0 / static_cast<double>(f.realSize); // FFTW does not normalise
    for (std::size_t c = 0; c < f.complexSize; ++c) {
        f.green[c][0] *= scale;
        f.green[c][1] *= scale;
    }
    // Global row -> padded index, from the owner table (same for every block layout).
    f.cellOfRow.assign(static_cast<std::size_t>(layout.globalCellCount()), 0);
    for (std::int64_t k = 0; k < N[2]; ++k)
        for (std::int64_t j = 0; j < N[1]; ++j)
            for (std::int64_t i = 0; i < N[0]; ++i)
                f.cellOfRow[static_cast<std::size_t>(layout.owner({i, j, k})->row)] =
                    static_cast<std::int64_t>(f.index(i, j, k));
    m_setupSeconds = MPI_Wtime() - t0;
}

FftFreeSpace::~FftFreeSpace() = default;

double FftFreeSpace::solve(CellField const& density, CellField& potential) {
    auto const& layout = *m_layout;
    std::size_t const cells = layout.cellsInBlock();
    int const count = static_cast<int>(layout.localBlockCount() * cells);
    std::vector<double> mine(static_cast<std::size_t>(count));
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b) {
        auto const rho = density.block(b);
        for (std::size_t c = 0; c < cells; ++c)
            mine[b * cells + c] = rho[layout.padOfInterior(c)];
    }
    // Ranks own consecutive rows in rank order, so a gather in rank order is in row order.
    std::vector<int> counts = m_comm.allGather(count);
    std::vector<int> displs(counts.size(), 0);
    std::exclusive_scan(counts.begin(), counts.end(), displs.begin(), 0);
    std::vector<double> all;
    if (m_comm.rank() == 0)
        all.resize(static_cast<std::size_t>(layout.globalCellCount()));
    core::Comm::check(MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(),
                                  displs.data(), MPI_DOUBLE, 0, m_comm.raw()),
                      "MPI_Gatherv");
    double seconds = 0.0;
    if (m_comm.rank() == 0) {
        auto& f = *m_fftw;
        double const t0 = MPI_Wtime();
        std::fill(f.real, f.real + f.realSize, 0.0);
        for (std::size_t row = 0; row < all.size(); ++row)
            f.real[f.cellOfRow[row]] = all[row];
        fftw_execute_dft_r2c(f.forward, f.real, f.spectrum);
        for (std::size_t c = 0; c < f.complexSize; ++c) {
            double const re = f.spectrum[c][0] * f.green[c][0] - f.spectrum[c][1] * f.green[c][1];
            double const im = f.spectrum[c][0] * f.green[c][1] + f.spectrum[c][1] * f.green[c][0];
            f.spectrum[c][0] = re;
            f.spectrum[c][1] = im;
        }
        fftw_execute_dft_c2r(f.backward, f.spectrum, f.real);
        for (std::size_t row = 0; row < all.size(); ++row)
            all[row] = f.real[f.cellOfRow[row]];
        seconds = MPI_Wtime() - t0;
    }
    core::Comm::check(MPI_Scatterv(all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                                   mine.data(), count, MPI_DOUBLE, 0, m_comm.raw()),
                      "MPI_Scatterv");
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b) {
        auto phi = potential.block(b);
        for (std::size_t c = 0; c < cells; ++c)
            phi[layout.padOfInterior(c)] = mine[b * cells + c];
    }
    return seconds;
}

} // namespace regolith::gravity
