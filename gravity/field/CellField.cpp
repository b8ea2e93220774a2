#include "gravity/field/CellField.hpp"

namespace regolith::gravity {

double CellField::localInteriorSum(int c) const {
    auto const& n = m_layout->cellsPerBlock();
    double sum = 0.0;
    for (std::size_t b = 0; b < m_layout->localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i)
                    sum += at(b, i, j, k, c);
    return sum;
}

} // namespace regolith::gravity
