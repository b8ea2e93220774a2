#pragma once
/// Which Poisson solver grid gravity uses (scene key gravity.poisson).
#include <string>

namespace regolith::gravity {

enum class PoissonMethod {
    /// "petsc" (default): distributed over the forest's blocks, free space or periodic, the
    /// set-up reused and each solve warm-started.
    Petsc,
    /// "fft": Hockney–Eastwood zero-padded convolution on rank 0 (FftFreeSpace), free space
    /// only; faster for a cold solve up to ~64³ cells on one node (docs/results.md).
    Fft,
};

/// Parses gravity.poisson ("petsc" | "fft"); throws core::InputError naming the key.
[[nodiscard]] PoissonMethod parsePoissonMethod(std::string const& name);

[[nodiscard]] char const* toString(PoissonMethod method);

} // namespace regolith::gravity
