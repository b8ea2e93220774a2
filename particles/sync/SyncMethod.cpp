#include "particles/sync/SyncMethod.hpp"

namespace regolith::particles {

std::string_view syncMethodName(SyncMethod m) {
    switch (m) {
    case SyncMethod::NextNeighbour:
        return "nns";
    case SyncMethod::ShadowOwner:
        return "sos";
    case SyncMethod::Hybrid:
        return "hybrid";
    }
    return "?";
}

std::optional<SyncMethod> parseSyncMethod(std::string_view name) {
    for (auto m : {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid})
        if (syncMethodName(m) == name)
            return m;
    return std::nullopt;
}

} // namespace regolith::particles
