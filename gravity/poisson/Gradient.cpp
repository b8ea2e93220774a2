#include "gravity/poisson/Gradient.hpp"

#include "core/Error.hpp"

#include <array>

namespace regolith::gravity {

void negativeGradient(CellField const& potential, CellField& acceleration, int order) {
    auto const& layout = potential.layout();
    if ((order != 2 && order != 4) || layout.ghost() < order / 2 ||
        acceleration.components() != 3 || &acceleration.layout() != &layout)
        throw core::Error("negativeGradient: order 2 or 4 with enough ghost layers and a "
                          "3-component field on the same layout expected");
    auto const& n = layout.cellsPerBlock();
    auto const& h = layout.spacing();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b) {
        auto const phi = potential.block(b);
        for (int a = 0; a < 3; ++a) {
            auto g = acceleration.block(b, a);
            std::array<int, 3> e{0, 0, 0};
            e[static_cast<std::size_t>(a)] = 1;
            double const inv2 = 1.0 / (2.0 * h[a]);
            double const inv12 = 1.0 / (12.0 * h[a]);
            for (int k = 0; k < n[2]; ++k)
                for (int j = 0; j < n[1]; ++j)
                    for (int i = 0; i < n[0]; ++i) {
                        auto at = [&](int s) {
                            return phi[layout.padIndex(i + s * e[0], j + s * e[1], k + s * e[2])];
                        };
                        double const d =
                            order == 2 ? (at(1) - at(-1)) * inv2
                                       : (-at(2) + 8.0 * at(1) - 8.0 * at(-1) + at(-2)) * inv12;
                        g[layout.padIndex(i, j, k)] = -d;
                    }
        }
    }
}

} // namespace regolith::gravity
