#include "particles/generators/GeneratorSpec.hpp"

namespace regolith::particles {

char const* kindName(ParticleSpec const& spec) {
    if (std::holds_alternative<LatticeSpec>(spec.kind))
        return "lattice";
    if (std::holds_alternative<ListSpec>(spec.kind))
        return "list";
    if (std::holds_alternative<FileSpec>(spec.kind))
        return "file";
    return "agglomerate";
}

} // namespace regolith::particles
