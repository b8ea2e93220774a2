#include "particles/sync/SyncMessages.hpp"

#include "core/Error.hpp"

#include <string>

namespace regolith::particles::sync_detail {

void writeFields(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i) {
    std::size_t const n = grainFieldComponents();
    for (std::size_t k = 0; k < n; ++k)
        b << (k < ps.fieldComponents() ? ps.fieldComponent(k, i) : 0.0);
}

std::vector<double> readFields(core::RecvBuffer& b) {
    std::vector<double> values(grainFieldComponents());
    for (double& v : values)
        b >> v;
    return values;
}

void writeHeader(core::SendBuffer& b, RecordKind kind, std::uint64_t targetBlock) {
    b << kind << targetBlock;
}

void writeFull(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i,
               core::Vec3 const& position, CopyImage const& image, BlockRef owner,
               std::vector<CopyRef> const& holders) {
    // writeRow<RowPart::Kept> of copy i, read from the storage in place, with the copy's
    // position and without the Shadow bit.
    constexpr std::size_t kPosition = grainQuantityIndex("position");
    constexpr std::size_t kFlags = grainQuantityIndex("flags");
    forEachGrainQuantity([&](auto k) {
        if constexpr (k.value == kPosition)
            b << position;
        else if constexpr (k.value == kFlags)
            b << Flags(ps.flags(i)).set(Flag::Shadow, false);
        else if constexpr (kGrainQuantity<k.value>.storage != GrainStorage::Elsewhere)
            b << ps.value<k.value>(i);
    });
    b << image << owner << ps.history(i).entries() << holders;
    writeFields(b, ps, i);
}

FullState readFull(core::RecvBuffer& b) {
    FullState s;
    ParticleInit& p = s.init;
    readRow<RowPart::Kept>(b, p);
    b >> p.image >> p.owner >> s.history >> s.holders;
    p.fields = readFields(b);
    return s;
}

void writeUpdate(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i,
                 core::Vec3 const& position, CopyImage const& oldImage, CopyImage const& newImage,
                 BlockRef owner) {
    b << ps.uid(i) << oldImage << newImage << position << ps.velocity(i) << ps.angularVelocity(i)
      << ps.orientation(i) << Flags(ps.flags(i)).set(Flag::Shadow, false) << owner
      << ps.history(i).entries();
    writeFields(b, ps, i);
}

UpdateState readUpdate(core::RecvBuffer& b) {
    UpdateState u;
    b >> u.uid >> u.oldImage >> u.newImage >> u.position >> u.velocity >> u.angularVelocity >>
        u.orientation >> u.flags >> u.owner >> u.history;
    u.fields = readFields(b);
    return u;
}

std::size_t addFull(ParticleStorage& ps, FullState const& s, bool master) {
    ParticleInit p = s.init;
    p.flags.set(Flag::Shadow, !master);
    std::size_t const i = ps.add(p);
    ps.history(i).assign(s.history);
    if (master)
        ps.shadowHolders(i) = s.holders;
    return i;
}

void applyUpdate(ParticleStorage& ps, std::size_t i, UpdateState const& u) {
    ps.receivePosition(i, u.position);
    ps.velocity(i) = u.velocity;
    ps.angularVelocity(i) = u.angularVelocity;
    ps.setOrientation(i, u.orientation);
    ps.setFlags(i, Flags(u.flags).set(Flag::Shadow, ps.flags(i).isShadow()));
    ps.setOwner(i, u.owner);
    ps.history(i).assign(u.history);
    ps.setFieldValues(i, u.fields);
}

void copyMotion(ParticleStorage const& from, std::size_t i, core::Vec3 const& position,
                ParticleStorage& to, std::size_t k) {
    to.receivePosition(k, position);
    to.velocity(k) = from.velocity(i);
    to.angularVelocity(k) = from.angularVelocity(i);
    to.setOrientation(k, from.orientation(i));
    if (!to.sharesHistory(k) && (!from.history(i).empty() || !to.history(k).empty()))
        to.history(k).assign(from.history(i).entries());
    for (std::size_t c = 0; c < from.fieldComponents(); ++c)
        to.fieldComponent(c, k) = from.fieldComponent(c, i);
}

void copyUpdate(ParticleStorage const& from, std::size_t i, core::Vec3 const& position,
                BlockRef owner, ParticleStorage& to, std::size_t k) {
    copyMotion(from, i, position, to, k);
    to.setFlags(k, Flags(from.flags(i)).set(Flag::Shadow, to.flags(k).isShadow()));
    to.setOwner(k, owner);
}

void touchedEntries(ParticleStorage const& ps, std::size_t i, std::uint32_t stamp,
                    std::vector<HistoryEntry>& out) {
    out.clear();
    for (HistoryEntry const& e : ps.history(i))
        if (e.stamp == stamp)
            out.push_back(e);
}

void addShare(ParticleStorage& master, std::size_t m, core::Vec3 const& force,
              core::Vec3 const& torque, std::span<HistoryEntry const> entries) {
    master.force(m) += force;
    master.torque(m) += torque;
    for (HistoryEntry const& e : entries)
        master.history(m).set(e);
}

bool hasShare(ParticleStorage const& ps, std::size_t i, std::span<HistoryEntry const> entries) {
    return !entries.empty() || !ps.force(i).isZero(0.0) || !ps.torque(i).isZero(0.0);
}

void addShadowShare(ParticleStorage& ps, std::size_t i, std::span<HistoryEntry const> entries,
                    ParticleStorage& master, std::size_t m) {
    if (!hasShare(ps, i, entries))
        return;
    addShare(master, m, ps.force(i), ps.torque(i), entries);
    ps.force(i).setZero();
    ps.torque(i).setZero();
}

void writeMotion(core::SendBuffer& b, ParticleStorage const& ps, std::size_t i,
                 std::size_t fields) {
    core::Vec3 const& x = ps.position(i);
    core::Vec3 const& v = ps.velocity(i);
    core::Vec3 const& w = ps.angularVelocity(i);
    double const motion[9] = {x.x(), x.y(), x.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()};
    std::span<HistoryEntry const> const history = ps.history(i).entries();
    bool const oriented = ps.storesOrientations();
    std::uint32_t const head[2] = {static_cast<std::uint32_t>(history.size()), oriented ? 1U : 0U};
    b.writeBytes(motion, sizeof motion);
    b.writeBytes(head, sizeof head);
    if (oriented)
        b << ps.orientation(i);
    b.writeBytes(history.data(), history.size_bytes());
    if (fields > 0)
        writeFields(b, ps, i);
}

void readMotion(core::RecvBuffer& b, ParticleStorage& ps, std::size_t k,
                std::vector<HistoryEntry>& history, std::size_t fields) {
    double motion[9];
    std::uint32_t head[2];
    b.readBytes(motion, sizeof motion, "a shadow's motion");
    b.readBytes(head, sizeof head, "a shadow's motion");
    ps.receivePosition(k, core::Vec3(motion[0], motion[1], motion[2]));
    ps.velocity(k) = core::Vec3(motion[3], motion[4], motion[5]);
    ps.angularVelocity(k) = core::Vec3(motion[6], motion[7], motion[8]);
    if (head[1] != 0) {
        core::Quat q;
        b >> q;
        ps.setOrientation(k, q);
    } else if (ps.storesOrientations()) {
        ps.setOrientation(k, core::Quat::Identity());
    }
    if (head[0] > b.remaining() / sizeof(HistoryEntry))
        throw core::Error("sync: malformed update message: a shadow's history claims " +
                          std::to_string(head[0]) + " entries");
    history.resize(head[0]);
    b.readBytes(history.data(), history.size() * sizeof(HistoryEntry), "a shadow's history");
    if (!history.empty() || !ps.history(k).empty())
        ps.history(k).assign(history);
    if (fields > 0)
        ps.setFieldValues(k, readFields(b));
}

} // namespace regolith::particles::sync_detail
