#pragma once
/// One master particle as the apps report it (checksum, `--dump`, conserved quantities): plain
/// data, independent of the particle storage; `--dump` writes the table entries marked kDump
/// (docs/design.md, "Dump": uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass, then the grain fields
/// a program declared).
#include "particles/storage/GrainQuantities.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace regolith::apps {

/// The table's quantities (particles/storage/GrainQuantities.hpp; the apps read uid, position,
/// velocity, angular velocity, radius and mass) and the declared grain fields.
struct MasterRecord : particles::GrainRow {
    /// The declared grain fields (particles/storage/GrainFields.hpp), for --dump's columns
    /// after the contract's; empty where only the state above is reported.
    std::vector<double> fields{};
};

/// The local masters visited one by one, in a fixed order, without a list of them: a call
/// `source(visit)` calls `visit(record)` for every master. The end-of-run summary of millions
/// of grains then needs no 96-byte record per grain beside the particle storage.
using MasterVisit = std::function<void(MasterRecord const&)>;
using MasterSource = std::function<void(MasterVisit const&)>;

/// The records of `masters` as a source (same order). `masters` must outlive the source.
[[nodiscard]] inline MasterSource sourceOf(std::span<MasterRecord const> masters) {
    return [masters](MasterVisit const& visit) {
        for (MasterRecord const& m : masters)
            visit(m);
    };
}

} // namespace regolith::apps
