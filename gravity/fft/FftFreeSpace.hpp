#pragma once
/// Free-space Poisson solve by FFT convolution (Hockney & Eastwood, "Computer Simulation
/// Using Particles", ch. 6: the density zero-padded to twice the grid per axis, convolved
/// with the sampled Green's function -G V / |r|), on rank 0 with FFTW: the density is
/// gathered there and the potential scattered back. The speed and accuracy reference of
/// the benchmark for the PETSc solve on uniform grids; not a scalable method (one rank does
/// all the work, memory ~ 3 x (2N)^3 doubles). No FFTW header here.
#include "core/mpi/Comm.hpp"
#include "gravity/field/CellField.hpp"

#include <memory>

namespace regolith::gravity {

class FftFreeSpace {
public:
    /// Plans the transforms and transforms the Green's function (rank 0), gathers the block
    /// table. Throws core::InputError on every rank for a periodic axis ("domain.periodic").
    /// Pre: `layout` outlives this object. COLLECTIVE over `comm`.
    FftFreeSpace(core::Comm const& comm, CellLayout const& layout, double G);
    ~FftFreeSpace();
    FftFreeSpace(FftFreeSpace const&) = delete;
    FftFreeSpace& operator=(FftFreeSpace const&) = delete;

    /// φ [length^2 / time^2] on the interior cells of `potential` from density component 0
    /// [mass / length^3]. Returns the seconds rank 0 spent in the transforms. COLLECTIVE.
    double solve(CellField const& density, CellField& potential);
    /// Seconds the constructor spent planning and transforming the Green's function.
    [[nodiscard]] double setupSeconds() const { return m_setupSeconds; }

private:
    struct Fftw;
    core::Comm m_comm;
    CellLayout const* m_layout;
    double m_setupSeconds = 0.0;
    std::unique_ptr<Fftw> m_fftw; ///< rank 0 only
};

} // namespace regolith::gravity
