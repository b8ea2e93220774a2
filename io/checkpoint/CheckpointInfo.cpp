#include "io/checkpoint/CheckpointInfo.hpp"

#include "io/checkpoint/GrainState.hpp"

#include <span>

namespace regolith::io {

namespace {

template <class T>
std::uint64_t mix(std::uint64_t h, T const& v) {
    return fnv1a(std::as_bytes(std::span<T const, 1>(&v, 1)), h);
}

} // namespace

std::uint64_t infoHash(CheckpointInfo const& info) {
    std::uint64_t h = 0xCBF29CE484222325ULL;
    h = mix(h, info.formatVersion);
    h = mix(h, info.step);
    h = mix(h, info.time);
    h = mix(h, info.dt);
    for (int k = 0; k < 3; ++k) {
        h = mix(h, info.domain.min[k]);
        h = mix(h, info.domain.max[k]);
        h = mix(h, static_cast<std::uint8_t>(info.periodic[static_cast<std::size_t>(k)]));
    }
    h = fnv1a(std::as_bytes(std::span(info.scene)), h);
    h = mix(h, info.scene.size()); // separates the two texts
    h = fnv1a(std::as_bytes(std::span(info.stateChecksum)), h);
    h = mix(h, info.grainCount);
    h = mix(h, info.historyCount);
    h = mix(h, info.gravityUpdates);
    h = mix(h, info.gravityPotentialEnergy);
    h = mix(h, info.gravitySinceUpdate);
    h = mix(h, info.gravityInterval);
    return h;
}

} // namespace regolith::io
