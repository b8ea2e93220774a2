#include "particles/storage/ParticleStorage.hpp"

#include "core/Error.hpp"
#include "core/memory/GentleGrowth.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

namespace regolith::particles {

template <class F>
void ParticleStorage::forEachArray(F&& f) {
    forEachGrainQuantity([&](auto k) {
        constexpr GrainStorage kept = kGrainQuantity<k.value>.storage;
        if constexpr (kept == GrainStorage::PerCopy)
            f(array<k.value>());
        else if constexpr (kept == GrainStorage::WhenNeeded) {
            if (!array<k.value>().empty())
                f(array<k.value>());
        }
    });
    f(m_invMass);
    f(m_invInertia);
    f(m_ownerSlot);
    f(m_image);
    f(m_shadowHolders);
    f(m_history);
    for (std::vector<double>& component : m_fields)
        f(component);
}

ParticleStorage::Index ParticleStorage::add(ParticleInit const& p) {
    touchLayout();
    if (p.uid == kInvalidUid)
        throw core::Error("ParticleStorage::add: invalid uid");
    Index const i = size();
    if (i >= CopyIndex::kNone)
        throw core::Error("ParticleStorage::add: more copies than 32-bit indices");
    if (!m_index.insert(CopyKey{p.uid, p.image}, static_cast<std::uint32_t>(i), keyAt()))
        throw core::Error("ParticleStorage::add: uid " + std::to_string(p.uid) +
                          (isZero(p.image) ? "" : " (periodic image)") + " is already stored");
    // Grain fields declared since the last copy was added: zero for the copies before.
    if (m_fields.size() < grainFieldComponents())
        m_fields.resize(grainFieldComponents(), std::vector<double>(i, 0.0));
    // Every array is full at once: grow all by a sixteenth, not by push_back's doubling (the
    // first shadow after a set-up reserved to the masters would double the whole storage).
    if (i == array<kUid>().capacity())
        forEachArray([i](auto& v) { v.reserve(core::gentleCapacity(i)); });
    // Empty array<kOrientation>(): not stored (size() is still i here, maybe 0).
    bool const storeOrientation = !array<kOrientation>().empty() || !isIdentityBits(p.orientation);
    if (storeOrientation && array<kOrientation>().empty())
        storeOrientations();
    forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        if constexpr (q.storage == GrainStorage::PerCopy)
            array<k.value>().push_back(p.*q.row);
    });
    if (storeOrientation)
        array<kOrientation>().push_back(p.orientation);
    m_invMass.push_back(0.0);
    m_invInertia.push_back(0.0);
    m_ownerSlot.push_back(ownerSlot(p.owner));
    m_image.push_back(p.image);
    m_shadowHolders.emplace_back();
    m_history.emplace_back();
    for (std::size_t c = 0; c < m_fields.size(); ++c)
        m_fields[c].push_back(c < p.fields.size() ? p.fields[c] : 0.0);
    updateInverses(i);
    if (tracing()) {
        core::reserveForAppend(m_traceTag);
        m_traceTag.push_back(kUntraced);
        m_traceJournal.push_back({static_cast<std::uint32_t>(i), kUntraced});
    }
    return i;
}

GrainRow ParticleStorage::row(Index i) const {
    GrainRow r;
    forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        if constexpr (q.storage != GrainStorage::Elsewhere)
            r.*q.row = value<k.value>(i);
    });
    return r;
}

std::vector<double> ParticleStorage::fieldValues(Index i) const {
    std::vector<double> values(m_fields.size());
    for (std::size_t c = 0; c < m_fields.size(); ++c)
        values[c] = m_fields[c][i];
    return values;
}

void ParticleStorage::setFieldValues(Index i, std::span<double const> values) {
    for (std::size_t c = 0; c < std::min(values.size(), m_fields.size()); ++c)
        m_fields[c][i] = values[c];
}

void ParticleStorage::remove(Index i) {
    touchLayout();
    Index const last = size() - 1;
    m_index.erase(key(i), keyAt());
    if (tracing()) {
        m_traceJournal.push_back({static_cast<std::uint32_t>(i), m_traceTag[i]});
        if (i != last)
            m_traceJournal.push_back({static_cast<std::uint32_t>(last), m_traceTag[last]});
        m_traceTag[i] = m_traceTag[last];
        m_traceTag.pop_back();
    }
    if (i != last) {
        // The index finds `last` through its key in the arrays: re-point it while the
        // arrays still hold that key at `last` too (before the pop).
        forEachArray([i, last](auto& v) { v[i] = std::move(v[last]); });
        m_index.assign(key(i), static_cast<std::uint32_t>(i), keyAt());
    }
    forEachArray([](auto& v) { v.pop_back(); });
}

bool ParticleStorage::removeUid(Uid uid, CopyImage const& image) {
    Index const i = find(uid, image);
    if (i == kNotFound)
        return false;
    remove(i);
    return true;
}

ParticleStorage::Index ParticleStorage::find(Uid uid, CopyImage const& image) const {
    std::uint32_t const i = m_index.find(CopyKey{uid, image}, keyAt());
    return i == CopyIndex::kNone ? kNotFound : Index{i};
}

void ParticleStorage::setImage(Index i, CopyImage const& image) {
    if (sameImage(image, m_image[i]))
        return;
    touchLayout();
    // The index confirms keys in m_image: drop the old key first, so that slot i is never
    // listed under two keys at once, then add the new one (or restore the old on failure).
    CopyImage const old = m_image[i];
    m_index.erase(key(i), keyAt());
    m_image[i] = image;
    if (!m_index.insert(CopyKey{array<kUid>()[i], image}, static_cast<std::uint32_t>(i), keyAt())) {
        m_image[i] = old;
        (void)m_index.insert(CopyKey{array<kUid>()[i], old}, static_cast<std::uint32_t>(i),
                             keyAt());
        throw core::Error("ParticleStorage::setImage: uid " + std::to_string(array<kUid>()[i]) +
                          " is already stored at that periodic image");
    }
    if (tracing()) { // its local position jumped: a new copy for the follower
        m_traceJournal.push_back({static_cast<std::uint32_t>(i), m_traceTag[i]});
        m_traceTag[i] = kUntraced;
    }
}

void ParticleStorage::moveByPeriods(Index i, core::Vec3 const& x) {
    touchLayout();
    array<kPosition>()[i] = x;
    if (tracing()) { // its local position jumped: a new copy for the follower
        m_traceJournal.push_back({static_cast<std::uint32_t>(i), m_traceTag[i]});
        m_traceTag[i] = kUntraced;
    }
}

void ParticleStorage::receivePosition(Index i, core::Vec3 const& x) {
    core::Vec3 const& old = array<kPosition>()[i];
    for (int a = 0; a < 3; ++a)
        if (m_wrapPeriod[a] > 0.0 && std::abs(x[a] - old[a]) > 0.5 * m_wrapPeriod[a]) {
            moveByPeriods(i, x);
            return;
        }
    position(i) = x;
}

void ParticleStorage::permute(std::span<Index const> newToOld) {
    touchLayout();
    Index const n = size();
    if (newToOld.size() != n)
        throw core::Error("ParticleStorage::permute: " + std::to_string(newToOld.size()) +
                          " indices for " + std::to_string(n) + " particles");
    std::vector<bool> seen(n, false);
    for (Index k : newToOld) {
        if (k >= n || seen[k])
            throw core::Error("ParticleStorage::permute: not a permutation");
        seen[k] = true;
    }
    forEachArray([newToOld](auto& v) {
        std::remove_reference_t<decltype(v)> out;
        out.reserve(v.capacity());
        for (Index k : newToOld)
            out.push_back(std::move(v[k]));
        v.swap(out);
    });
    // The index's slots hold old indices whose keys the arrays no longer hold there: rebuild.
    m_index.clear();
    m_index.reserve(n);
    for (Index k = 0; k < n; ++k)
        (void)m_index.insert(key(k), static_cast<std::uint32_t>(k), keyAt());
    m_traceBroken = tracing();
}

void ParticleStorage::reserve(std::size_t n) {
    forEachArray([n](auto& v) { v.reserve(n); });
    m_index.reserve(n);
}

void ParticleStorage::storeOrientations() {
    array<kOrientation>().reserve(array<kUid>().capacity());
    array<kOrientation>().assign(size(), kIdentityOrientation);
}

void ParticleStorage::shareHistories(std::span<std::array<Index, 2> const> shared) {
    stopSharingHistories();
    if (shared.empty())
        return;
    for (auto const& [shadow, master] : shared)
        if (shadow >= size() || master >= size() ||
            array<kUid>()[shadow] != array<kUid>()[master] || !flags(shadow).isShadow() ||
            !flags(master).isMaster())
            throw core::Error("ParticleStorage::shareHistories: copy " + std::to_string(shadow) +
                              " is not a shadow of the master at " + std::to_string(master));
    m_historyOf.resize(size());
    for (std::size_t k = 0; k < m_historyOf.size(); ++k)
        m_historyOf[k] = static_cast<std::uint32_t>(k);
    for (auto const& [shadow, master] : shared)
        m_historyOf[shadow] = static_cast<std::uint32_t>(master);
}

void ParticleStorage::stopSharingHistories() {
    for (std::size_t k = 0; k < m_historyOf.size(); ++k)
        if (m_historyOf[k] != k)
            m_history[k].assign(m_history[m_historyOf[k]].entries());
    m_historyOf.clear();
}

void ParticleStorage::copyMastersHistoriesToShadows() {
    for (Index k = 0, n = size(); k < n; ++k) {
        if (!flags(k).isShadow())
            continue;
        Index const m = find(array<kUid>()[k]);
        if (m != kNotFound && flags(m).isMaster())
            m_history[k].assign(m_history[m].entries());
    }
}

void ParticleStorage::clear() {
    touchLayout();
    forEachArray([](auto& v) { v.clear(); });
    m_owners.clear();
    m_lastOwnerSlot = 0;
    m_index.clear();
    m_traceTag.clear();
    m_traceJournal.clear();
    m_traceBroken = tracing();
}

std::uint64_t ParticleStorage::startTracing() {
    // Unique over all storages of the process, so that a follower fed another storage (or
    // this one after a restart of the trace) notices.
    static std::atomic<std::uint64_t> sessions{0};
    m_traceSession = ++sessions;
    m_traceBroken = false;
    m_traceJournal.clear();
    m_traceTag.reserve(core::gentleCapacity(size())); // arrivals: no reallocation (peak)
    m_traceTag.resize(size());
    for (Index k = 0, n = size(); k < n; ++k)
        m_traceTag[k] = static_cast<std::uint32_t>(k);
    return m_traceSession;
}

void ParticleStorage::setRadius(Index i, double radius) {
    if (radius != array<kRadius>()[i]) {
        touchLayout(); // which blocks need copies depends on the radii
        if (tracing())
            m_traceBroken = true; // a neighbour list's reach depends on the radii
    }
    array<kRadius>()[i] = radius;
    updateInverses(i);
}

void ParticleStorage::setMass(Index i, double mass) {
    array<kMass>()[i] = mass;
    updateInverses(i);
}

void ParticleStorage::setFlags(Index i, Flags flags) {
    bool const fixedChanged = flags.isFixed() != array<kFlags>()[i].isFixed();
    if (tracing() && fixedChanged)
        m_traceBroken = true; // a neighbour list skips pairs of two Fixed copies
    array<kFlags>()[i] = flags;
    if (fixedChanged) // the sync sets flags every step; inverses depend only on Fixed
        updateInverses(i);
}

void ParticleStorage::updateInverses(Index i) {
    if (array<kFlags>()[i].isFixed()) {
        m_invMass[i] = 0.0;
        m_invInertia[i] = 0.0;
        return;
    }
    // Solid sphere about its centre: I = 2/5 m r^2. Invalid mass or radius gives inf or NaN
    // here; validateParticles reports those before a run starts.
    double const r = array<kRadius>()[i];
    m_invMass[i] = 1.0 / array<kMass>()[i];
    m_invInertia[i] = 1.0 / (0.4 * array<kMass>()[i] * r * r);
}

std::uint32_t ParticleStorage::ownerSlot(BlockRef const& owner) {
    if (m_lastOwnerSlot < m_owners.size() && m_owners[m_lastOwnerSlot] == owner)
        return m_lastOwnerSlot;
    for (std::size_t s = 0; s < m_owners.size(); ++s)
        if (m_owners[s] == owner)
            return m_lastOwnerSlot = static_cast<std::uint32_t>(s);
    m_owners.push_back(owner);
    return m_lastOwnerSlot = static_cast<std::uint32_t>(m_owners.size() - 1);
}

void ParticleStorage::resetForces() {
    // Whole arrays: Eigen's stores may alias the vectors' own pointers, so element by
    // element every store reloaded them.
    std::fill(array<kForce>().begin(), array<kForce>().end(), core::Vec3::Zero());
    std::fill(array<kTorque>().begin(), array<kTorque>().end(), core::Vec3::Zero());
}

std::size_t ParticleStorage::countMasters() const {
    std::size_t n = 0;
    for (Flags f : array<kFlags>())
        n += f.isMaster() ? 1 : 0;
    return n;
}

std::size_t ParticleStorage::bytes() const {
    std::size_t b = 0;
    auto add = [&b](auto const& v) { b += v.capacity() * sizeof(v[0]); };
    std::apply([&add](auto const&... v) { (add(v), ...); }, m_state);
    add(m_invMass);
    add(m_invInertia);
    add(m_ownerSlot);
    add(m_owners);
    add(m_image);
    add(m_shadowHolders);
    add(m_history);
    add(m_traceTag);
    add(m_traceJournal);
    for (std::vector<double> const& component : m_fields)
        add(component);
    for (auto const& h : m_shadowHolders)
        b += h.heapBytes();
    for (auto const& h : m_history)
        b += h.heapBytes();
    b += m_index.bytes();
    return b;
}

} // namespace regolith::particles
