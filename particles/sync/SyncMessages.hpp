#pragma once
/// The records the synchronisation sends between blocks. Every record starts with its kind
/// and the target block; records for one rank are aggregated into one message per exchange.
#include "core/mpi/Buffer.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace regolith::particles {

/// Packing of a history entry (Eigen vectors are not trivially copyable).
inline core::SendBuffer& operator<<(core::SendBuffer& b, HistoryEntry const& e) {
    return b << e.partner << e.spring << e.stamp;
}
inline core::RecvBuffer& operator>>(core::RecvBuffer& b, HistoryEntry& e) {
    return b >> e.partner >> e.spring >> e.stamp;
}

} // namespace regolith::particles

namespace regolith::particles::sync_detail {

enum class RecordKind : std::uint8_t {
    Copy = 1,          ///< create a shadow: full state incl. contact history (Alg. 1/2 "create")
    Update = 2,        ///< what changes each step, the (new) owner and image (Alg. 1/2 "update")
    Promote = 3,       ///< ownership transfer: full state, force, torque and the shadow holders
    Remove = 4,        ///< delete a shadow (master's order, or the grain left the domain)
    HolderAdded = 5,   ///< SOS round 2 -> owner: a new shadow exists at `holder`
    HolderRemoved = 6, ///< SOS round 2 -> owner: the shadow at `holder` was dropped
    ForgetSent = 7,    ///< SOS round 2 -> neighbours: drop this copy from your sent-cache
    Force = 8,         ///< shadow -> master: force, torque, touched history entries
    ForceRecords = 9,  ///< shadow -> master, reproducible: per-contact force records
};

/// A particle's complete state as it travels (creation and promotion): the table's entries kept
/// by the storage (force and torque among them), the copy's place, its history and holders.
struct FullState {
    ParticleInit init;
    std::vector<HistoryEntry> history;
    std::vector<CopyRef> holders;
};

/// Which table entries (GrainQuantities.hpp) a row carries through a buffer.
enum class RowPart : std::uint8_t {
    Kept,  ///< those ParticleStorage keeps (a copy's state)
    Every, ///< all of them (a checkpoint's grain on its way to its owner)
};

/// Writes the entries `part` of `row` (a GrainRow, or a row holding every entry, as
/// io::GrainState) in the table's order.
template <RowPart part, class Row>
void writeRow(core::SendBuffer& b, Row const& row) {
    forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        if constexpr (part == RowPart::Every || q.storage != GrainStorage::Elsewhere)
            b << row.*q.row;
    });
}
/// Reads what writeRow<part> wrote into `row` (other entries unchanged).
template <RowPart part, class Row>
void readRow(core::RecvBuffer& b, Row& row) {
    forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        if constexpr (part == RowPart::Every || q.storage != GrainStorage::Elsewhere)
            b >> row.*q.row;
    });
}

/// What an update carries.
struct UpdateState {
    Uid uid = kInvalidUid;
    CopyImage oldImage = kNoImage; ///< key of the copy at the receiver
    CopyImage newImage = kNoImage;
    core::Vec3 position = core::Vec3::Zero();
    core::Vec3 velocity = core::Vec3::Zero();
    core::Vec3 angularVelocity = core::Vec3::Zero();
    core::Quat orientation = core::Quat::Identity();
    Flags flags{};
    BlockRef owner{};
    std::vector<HistoryEntry> history;
    std::vector<double> fields; ///< the grain fields (GrainFields.hpp)
};

void writeHeader(core::SendBuffer& b, RecordKind kind, std::uint64_t targetBlock);

/// The grain fields of copy i of `ps` (GrainFields.hpp): grainFieldComponents() doubles,
/// declared alike on every rank; nothing when none is declared.
void writeFields(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i);
[[nodiscard]] std::vector<double> readFields(core::RecvBuffer& b);

/// Full state of copy `i` of `ps`, as a copy with `image` owned by `owner`.
void writeFull(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i,
               core::Vec3 const& position, CopyImage const& image, BlockRef owner,
               std::vector<CopyRef> const& holders);
FullState readFull(core::RecvBuffer& b);

void writeUpdate(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i,
                 core::Vec3 const& position, CopyImage const& oldImage, CopyImage const& newImage,
                 BlockRef owner);
UpdateState readUpdate(core::RecvBuffer& b);

/// Adds `s` to `ps` as a shadow (flags without Shadow get it set) or master; returns index.
std::size_t addFull(ParticleStorage& ps, FullState const& s, bool master);
/// Overwrites the dynamic state of copy i with `u` (image is re-keyed by the caller).
void applyUpdate(ParticleStorage& ps, std::size_t i, UpdateState const& u);
/// What writeUpdate + readUpdate + applyUpdate do for a shadow on this rank that keeps its
/// image, without the buffer: copy k of `to` gets master i's state with `position` and `owner`.
void copyUpdate(ParticleStorage const& from, std::size_t i, core::Vec3 const& position,
                BlockRef owner, ParticleStorage& to, std::size_t k);
/// copyUpdate's motion part: position, velocities, orientation, contact history and grain
/// fields, for a
/// shadow whose flags and owner are already its master's (along the update list between two
/// refreshes: nothing changes a master's flags or block there; checkSyncInvariants compares
/// both).
void copyMotion(ParticleStorage const& from, std::size_t i, core::Vec3 const& position,
                ParticleStorage& to, std::size_t k);

/// copyMotion through a message: what the owner sends of master i (its position is every
/// copy's canonical position; its orientation only if its storage keeps any, else it is the
/// identity), and what the shadow's rank makes of it, with copyMotion's bits. One record:
/// position, velocity and angular velocity in one piece, then the number of history entries
/// and whether an orientation follows, then those. `fields`: grainFieldComponents(), asked once
/// per message (most scenes declare none).
void writeMotion(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i, std::size_t fields);
void readMotion(core::RecvBuffer& b, ParticleStorage& ps, std::size_t k,
                std::vector<HistoryEntry>& history, std::size_t fields);

/// The history entries of copy i of `ps` stamped `stamp` (evaluated in this pass), into `out`.
void touchedEntries(ParticleStorage const& ps, std::size_t i, std::uint32_t stamp,
                    std::vector<HistoryEntry>& out);
/// What a Force record does on arrival: adds a shadow's force, torque and touched history
/// `entries` to master m of `master`.
void addShare(ParticleStorage& master, std::size_t m, core::Vec3 const& force,
              core::Vec3 const& torque, std::span<HistoryEntry const> entries);
/// Whether shadow i of `ps` has a share to send its master: touched `entries`, or a force or
/// torque (most shadows of a gas touch nothing and are skipped).
[[nodiscard]] bool hasShare(ParticleStorage const& ps, std::size_t i,
                            std::span<HistoryEntry const> entries);
/// Whether shadow i of `ps` may have a share at all (a history entry, a force or a torque):
/// inline, before touchedEntries and hasShare, for the shadows of a gas, most of which touch
/// nothing.
[[nodiscard]] inline bool mayHaveShare(ParticleStorage const& ps, std::size_t i) {
    return !ps.history(i).empty() || !ps.force(i).isZero(0.0) || !ps.torque(i).isZero(0.0);
}
/// addShare for a shadow on this rank: adds shadow i's force and
/// torque and `entries` (touchedEntries) to master m of `master` and zeroes the shadow's force
/// and torque -- unless there is nothing to add (no entry, zero force and torque).
void addShadowShare(ParticleStorage& ps, std::size_t i, std::span<HistoryEntry const> entries,
                    ParticleStorage& master, std::size_t m);

} // namespace regolith::particles::sync_detail
