#include "coupling/simulation/Placement.hpp"

#include <utility>

namespace regolith::coupling {

Placement placeBlocks(core::Comm const& comm, domain::ForestSpec const& spec,
                      domain::BlockWeight const& weight, domain::Subdomains subdomains) {
    auto [blocks, cut] = domain::BlockForest::blocksAnd(comm, spec, weight, subdomains);
    Placement p;
    p.spec = spec;
    p.forest = std::make_unique<domain::BlockForest>(std::move(blocks));
    p.particleForest = std::make_unique<domain::BlockForest>(std::move(cut));
    p.local = std::make_unique<particles::LocalParticles>(*p.particleForest);
    return p;
}

} // namespace regolith::coupling
