#pragma once
/// g = -∇φ on cell centres by centred differences, a pure kernel over the padded block
/// arrays (no MPI): second order, (φ[i+1] - φ[i-1]) / 2h, or fourth order,
/// (-φ[i+2] + 8φ[i+1] - 8φ[i-1] + φ[i-2]) / 12h.
#include "gravity/field/CellField.hpp"

namespace regolith::gravity {

/// Writes the 3 components of -∇φ into the interior cells of `acceleration` (3 components,
/// same layout) [length / time^2]. Pre: order 2 or 4; the ghost cells of `potential` up to
/// order / 2 layers are filled (ghost exchange and boundary values). Local.
void negativeGradient(CellField const& potential, CellField& acceleration, int order);

} // namespace regolith::gravity
