#include "particles/generators/GeneratorSpec.hpp"

#include "core/random/CounterRng.hpp"

namespace regolith::particles {

double RadiusRange::draw(std::uint64_t uid) const {
    if (!(min < max))
        return min;
    core::random::CounterRng rng(seed, uid, kRadiusStream);
    return rng.uniform(min, max);
}

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
