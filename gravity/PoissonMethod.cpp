#include "gravity/PoissonMethod.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

namespace regolith::gravity {

PoissonMethod parsePoissonMethod(std::string const& name) {
    if (name == "petsc")
        return PoissonMethod::Petsc;
    if (name == "fft")
        return PoissonMethod::Fft;
    throw core::InputError(
        fmt::format("gravity.poisson: expected \"petsc\" or \"fft\", got \"{}\"", name));
}

char const* toString(PoissonMethod method) {
    return method == PoissonMethod::Fft ? "fft" : "petsc";
}

} // namespace regolith::gravity
