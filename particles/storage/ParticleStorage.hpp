#pragma once
/// Structure-of-arrays storage of the spheres of one block (mesa_pd's `ParticleStorage`):
/// one contiguous array per property, so kernels stream only what they touch.
#include "core/math/Vec3.hpp"
#include "particles/storage/ContactHistory.hpp"
#include "particles/storage/CopyImage.hpp"
#include "particles/storage/CopyIndex.hpp"
#include "particles/storage/GrainFields.hpp"
#include "particles/storage/GrainQuantities.hpp"
#include "particles/storage/ParticleFlags.hpp"
#include "particles/storage/ThinList.hpp"
#include "particles/storage/Uid.hpp"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <tuple>
#include <vector>

namespace regolith::particles {

/// A block of the forest on a rank: who owns a master, who holds a shadow.
struct BlockRef {
    int rank = -1;
    std::uint64_t block = 0;
    friend bool operator==(BlockRef const&, BlockRef const&) = default;
    friend auto operator<=>(BlockRef const&, BlockRef const&) = default;
};

/// One copy of a particle somewhere: the block holding it and the copy's periodic image.
struct CopyRef {
    int rank = -1;
    std::uint64_t block = 0;
    CopyImage image = kNoImage;
    [[nodiscard]] BlockRef blockRef() const { return {rank, block}; }
    friend bool operator==(CopyRef const& a, CopyRef const& b) {
        return a.rank == b.rank && a.block == b.block && sameImage(a.image, b.image);
    }
    friend auto operator<=>(CopyRef const&, CopyRef const&) = default;
};

/// The shadow holders of a master: one pointer per copy, null while empty (ThinList).
using HolderList = ThinList<CopyRef>;

/// Everything needed to create a particle: its built-in state (GrainRow), where its copy lives
/// and its grain fields. Contact history starts empty.
struct ParticleInit : GrainRow {
    BlockRef owner{};
    CopyImage image = kNoImage; ///< see CopyImage.hpp; a master's is always kNoImage
    /// The declared grain fields' components (GrainFields.hpp, declaration order); those
    /// missing are 0.
    std::vector<double> fields;
};

/// One change of the storage seen by a trace (see ParticleStorage::startTracing): slot `index`
/// was written, added or dropped; `previous` is the tag the slot held before (kUntraced for a
/// slot that was new).
struct TraceChange {
    std::uint32_t index = 0;
    std::uint32_t previous = 0;
};

/// SoA particle storage with a (uid, image) -> index map.
///
/// Invariants: `find(uid(i), image(i)) == i` for every index, (uid, image) keys are unique (a
/// block that is its own periodic neighbour may hold one particle at several images); `invMass` and
/// `invInertia` follow mass, radius and the Fixed flag (zero when fixed; a sphere's inertia
/// is 2/5 m r^2). Adding is amortised O(1); removing is
/// O(1) by moving the last particle into the freed slot, which changes that particle's index (never
/// its uid). Indices are therefore only valid until the next removal.
class ParticleStorage {
public:
    using Index = std::size_t;
    static constexpr Index kNotFound = std::numeric_limits<Index>::max();
    /// The value type of table entry K (GrainQuantities.hpp).
    template <std::size_t K>
    using ValueOf =
        typename std::tuple_element_t<K, std::remove_cv_t<decltype(kGrainQuantities)>>::Value;

    /// Appends a particle and returns its index. Throws core::Error if the uid is kInvalidUid
    /// or (uid, image) is already stored. Values are not checked here (see validateParticles).
    Index add(ParticleInit const& p);
    /// Removes the particle at `i` (< size()) by swap-with-last.
    void remove(Index i);
    /// Removes the copy (uid, image); returns false if there is none.
    bool removeUid(Uid uid, CopyImage const& image = kNoImage);
    /// Index of the copy (uid, image), or kNotFound. Without an image: the unshifted copy (a
    /// master, or a shadow that needs no periodic shift).
    [[nodiscard]] Index find(Uid uid, CopyImage const& image = kNoImage) const;
    [[nodiscard]] bool contains(Uid uid, CopyImage const& image = kNoImage) const {
        return find(uid, image) != kNotFound;
    }
    /// Starts loading what find(uid, image) reads first (a hint; no effect on results; always
    /// inlined, see CopyIndex::prefetch).
    [[gnu::always_inline]] void prefetchFind(Uid uid, CopyImage const& image = kNoImage) const {
        m_index.prefetch(CopyKey{uid, image});
    }

    /// Reorders the particles: new index k holds the particle that had index `newToOld[k]`
    /// (mesa_pd's ParticleStorage::sort). Used to restore spatial locality, e.g. with
    /// ContactDetector::spatialOrder. Throws core::Error unless `newToOld` is a permutation of
    /// [0, size()). O(N) time and one temporary copy of each array.
    void permute(std::span<Index const> newToOld);

    [[nodiscard]] std::size_t size() const { return array<kUid>().size(); }
    [[nodiscard]] bool empty() const { return array<kUid>().empty(); }
    void reserve(std::size_t n);
    void clear();

    // ---- per-particle access (i < size()) ----------------------------------------------
    /// Table entry K's value of copy i (K kept here: PerCopy or WhenNeeded).
    template <std::size_t K>
    [[nodiscard]] ValueOf<K> const& value(Index i) const {
        constexpr GrainStorage kept = kGrainQuantity<K>.storage;
        static_assert(kept != GrainStorage::Elsewhere, "not kept by ParticleStorage");
        if constexpr (kept == GrainStorage::WhenNeeded) {
            static ValueOf<K> const unset = GrainRow{}.*kGrainQuantity<K>.row;
            return array<K>().empty() ? unset : array<K>()[i];
        } else
            return array<K>()[i];
    }
    /// The kept table entries of copy i as a row (those kept Elsewhere: GrainRow's defaults).
    [[nodiscard]] GrainRow row(Index i) const;
    [[nodiscard]] Uid uid(Index i) const { return array<kUid>()[i]; }
    [[nodiscard]] core::Vec3& position(Index i) { return array<kPosition>()[i]; }
    [[nodiscard]] core::Vec3 const& position(Index i) const { return array<kPosition>()[i]; }
    [[nodiscard]] core::Vec3& velocity(Index i) { return array<kVelocity>()[i]; }
    [[nodiscard]] core::Vec3 const& velocity(Index i) const { return array<kVelocity>()[i]; }
    [[nodiscard]] core::Vec3& angularVelocity(Index i) { return array<kAngularVelocity>()[i]; }
    [[nodiscard]] core::Vec3 const& angularVelocity(Index i) const {
        return array<kAngularVelocity>()[i];
    }
    /// The identity until some copy of this storage was given another orientation (see
    /// storesOrientations).
    [[nodiscard]] core::Quat const& orientation(Index i) const {
        return array<kOrientation>().empty() ? kIdentityOrientation : array<kOrientation>()[i];
    }
    /// Sets the orientation of copy i; the first orientation other than the identity makes
    /// the storage keep one per copy from then on.
    void setOrientation(Index i, core::Quat const& q) {
        if (array<kOrientation>().empty()) {
            if (isIdentityBits(q))
                return;
            storeOrientations();
        }
        array<kOrientation>()[i] = q;
    }
    /// Does the storage keep an orientation per copy? Not until a copy gets another than the
    /// identity (and again not once the storage is empty): spheres whose orientation is not
    /// integrated (time.orientation = false) cost no 32 bytes per copy (docs/notes/memory.md).
    [[nodiscard]] bool storesOrientations() const { return !array<kOrientation>().empty(); }
    [[nodiscard]] core::Vec3& force(Index i) { return array<kForce>()[i]; }
    [[nodiscard]] core::Vec3 const& force(Index i) const { return array<kForce>()[i]; }
    [[nodiscard]] core::Vec3& torque(Index i) { return array<kTorque>()[i]; }
    [[nodiscard]] core::Vec3 const& torque(Index i) const { return array<kTorque>()[i]; }
    [[nodiscard]] double radius(Index i) const { return array<kRadius>()[i]; }
    [[nodiscard]] double mass(Index i) const { return array<kMass>()[i]; }
    /// 1 / mass, 0 for a Fixed particle. Stored, not computed on use: recomputing both
    /// inverses in the integrators' loops (two divisions per grain and half-step) cost ~7 %
    /// of the sparse gas's step rate for 16 bytes per copy (docs/notes/memory.md).
    [[nodiscard]] double invMass(Index i) const { return m_invMass[i]; }
    /// Inverse of the (scalar) moment of inertia of the sphere about its centre.
    [[nodiscard]] double invInertia(Index i) const { return m_invInertia[i]; }
    [[nodiscard]] Flags flags(Index i) const { return array<kFlags>()[i]; }
    [[nodiscard]] std::uint32_t type(Index i) const { return array<kType>()[i]; }
    [[nodiscard]] BlockRef owner(Index i) const { return m_owners[m_ownerSlot[i]]; }
    [[nodiscard]] CopyImage const& image(Index i) const { return m_image[i]; }
    [[nodiscard]] CopyKey key(Index i) const { return {array<kUid>()[i], m_image[i]}; }
    /// Where the master knows its shadows to be (masters only; sorted, unique).
    [[nodiscard]] HolderList& shadowHolders(Index i) { return m_shadowHolders[i]; }
    [[nodiscard]] HolderList const& shadowHolders(Index i) const { return m_shadowHolders[i]; }
    [[nodiscard]] ContactHistory& history(Index i) { return m_history[i]; }
    [[nodiscard]] ContactHistory const& history(Index i) const { return m_history[i]; }
    /// The history whose springs copy i's pairs use: its own, or its master's while this
    /// storage holds both and shareHistories() said so.
    [[nodiscard]] ContactHistory& pairHistory(Index i) {
        return m_history[m_historyOf.empty() ? i : m_historyOf[i]];
    }
    /// Whether copy i's pairs use another copy's history (its own is then not kept current).
    [[nodiscard]] bool sharesHistory(Index i) const {
        return !m_historyOf.empty() && m_historyOf[i] != i;
    }
    /// From now until the layout changes or stopSharingHistories(), the pairs of each shadow
    /// `shared[n][0]` use the history of its master `shared[n][1]` (same grain, this storage):
    /// a spring is then written where the force reduction would have brought it, and the
    /// update need not copy the history to the shadow. Copy i's own history is current again
    /// when the sharing stops.
    void shareHistories(std::span<std::array<Index, 2> const> shared);
    void stopSharingHistories();
    /// Stops the sharing without bringing the shadows' own histories up to date: for a caller
    /// that shares them again, or calls copyMastersHistoriesToShadows(), before anything reads
    /// a shadow's own history (ParticleSync's calls along the update list).
    void forgetSharedHistories() { m_historyOf.clear(); }
    /// Each shadow whose master lies in this storage takes a copy of the master's history:
    /// what stopSharingHistories() would have done, after forgetSharedHistories().
    void copyMastersHistoriesToShadows();

    /// Component `c` of the grain field `id` (GrainFields.hpp) of copy i; the field was declared
    /// before the copy was added.
    [[nodiscard]] double& field(GrainFieldId id, Index i, std::size_t c = 0) {
        return m_fields[id.offset + c][i];
    }
    [[nodiscard]] double field(GrainFieldId id, Index i, std::size_t c = 0) const {
        return m_fields[id.offset + c][i];
    }
    /// Component `k` of all declared components (< fieldComponents()) of copy i.
    [[nodiscard]] double& fieldComponent(std::size_t k, Index i) { return m_fields[k][i]; }
    [[nodiscard]] double fieldComponent(std::size_t k, Index i) const { return m_fields[k][i]; }
    /// Every declared grain field's components of copy i (ParticleInit::fields' order).
    [[nodiscard]] std::vector<double> fieldValues(Index i) const;
    /// Sets them from `values` (those missing: unchanged).
    void setFieldValues(Index i, std::span<double const> values);
    /// The grain-field components this storage keeps (grainFieldComponents() once a copy was
    /// added after the last declaration).
    [[nodiscard]] std::size_t fieldComponents() const { return m_fields.size(); }

    /// Setters for properties that others depend on (inverse mass and inertia; a radius
    /// change also breaks a running trace, see startTracing).
    void setRadius(Index i, double radius);
    void setMass(Index i, double mass);
    void setFlags(Index i, Flags flags);
    void setType(Index i, std::uint32_t type) { array<kType>()[i] = type; }
    void setOwner(Index i, BlockRef owner) { m_ownerSlot[i] = ownerSlot(owner); }
    /// Re-keys copy i to `image`; throws core::Error if (uid, image) is held already.
    void setImage(Index i, CopyImage const& image);
    /// Moves copy i to `x`, its position wrapped by whole periods along an axis where no image
    /// is kept (PeriodicFrame::wrapped): a new copy for a running trace, as setImage.
    void moveByPeriods(Index i, core::Vec3 const& x);
    /// The periods along the axes where no image is kept (wrappedAxes), 0 on the others.
    void setWrapPeriod(core::Vec3 const& period) { m_wrapPeriod = period; }
    [[nodiscard]] core::Vec3 const& wrapPeriod() const { return m_wrapPeriod; }
    /// Writes the position of copy i as the synchronisation received it from its master: a
    /// jump of more than half a period along a wrapped axis is the master wrapping there, a
    /// new copy for a running trace (moveByPeriods); anything else a plain write.
    void receivePosition(Index i, core::Vec3 const& x);

    // ---- bulk access ---------------------------------------------------------------------
    [[nodiscard]] std::vector<Uid> const& uids() const { return array<kUid>(); }
    [[nodiscard]] std::vector<core::Vec3> const& positions() const { return array<kPosition>(); }
    [[nodiscard]] std::vector<core::Vec3> const& velocities() const { return array<kVelocity>(); }
    [[nodiscard]] std::vector<core::Vec3> const& angularVelocities() const {
        return array<kAngularVelocity>();
    }
    [[nodiscard]] std::vector<double> const& radii() const { return array<kRadius>(); }
    [[nodiscard]] std::vector<double> const& invMasses() const { return m_invMass; }
    [[nodiscard]] std::vector<double> const& invInertias() const { return m_invInertia; }
    [[nodiscard]] std::vector<CopyImage> const& images() const { return m_image; }
    [[nodiscard]] std::vector<Flags> const& allFlags() const { return array<kFlags>(); }

    /// Zeroes force and torque of every particle (masters and shadows).
    void resetForces();
    /// Calls `f(i)` for every particle.
    template <class F>
    void forEach(F&& f) const {
        for (Index i = 0, n = size(); i < n; ++i)
            f(i);
    }
    /// Calls `f(i)` for every master (not Shadow).
    template <class F>
    void forEachMaster(F&& f) const {
        for (Index i = 0, n = size(); i < n; ++i)
            if (array<kFlags>()[i].isMaster())
                f(i);
    }
    [[nodiscard]] std::size_t countMasters() const;

    // ---- tracing: let an index-based structure (VerletList) follow the storage's changes ----
    /// The tag of a copy added (or re-keyed to another image) since tracing started.
    static constexpr std::uint32_t kUntraced = std::numeric_limits<std::uint32_t>::max();
    /// Starts (or restarts) tracing: every copy gets tag = its index, the journal is emptied,
    /// and from now on every add, remove and setImage moves the tags with the copies (a copy
    /// added or re-keyed gets kUntraced) and appends the slots it wrote to the journal. A
    /// permute, clear, radius change or change of the Fixed flag breaks the trace (traceBroken()):
    /// the follower must start again. Returns a number that identifies this trace among all
    /// storages.
    std::uint64_t startTracing();
    [[nodiscard]] bool tracing() const { return m_traceSession != 0; }
    /// The identity of the running trace (0: none).
    [[nodiscard]] std::uint64_t traceSession() const { return m_traceSession; }
    [[nodiscard]] bool traceBroken() const { return m_traceBroken; }
    [[nodiscard]] std::uint32_t traceTag(Index i) const { return m_traceTag[i]; }
    /// Names a copy for the follower (not journaled). Pre: tracing().
    void setTraceTag(Index i, std::uint32_t tag) { m_traceTag[i] = tag; }
    [[nodiscard]] std::span<TraceChange const> traceJournal() const { return m_traceJournal; }
    void clearTraceJournal() { m_traceJournal.clear(); }

    /// A number that changes whenever a copy may have changed index or key (add, remove,
    /// setImage, permute, clear) or radius, unique among all storages of the process: a
    /// structure holding indices into this storage (or decisions on its radii) is valid while
    /// it stays the same.
    [[nodiscard]] std::uint64_t layoutRevision() const { return m_layoutRevision; }

    /// Bytes held by the storage: array capacities, heap of histories and shadow-holder lists,
    /// and an estimate of the uid map (buckets plus one node per entry).
    [[nodiscard]] std::size_t bytes() const;

private:
    static inline core::Quat const kIdentityOrientation = core::Quat::Identity();
    /// Bit for bit the identity (-0.0 is not 0.0 here: a shadow must get its master's bits).
    [[nodiscard]] static bool isIdentityBits(core::Quat const& q) {
        return std::memcmp(q.coeffs().data(), kIdentityOrientation.coeffs().data(),
                           4 * sizeof(double)) == 0;
    }

    /// One array per table entry (GrainQuantities.hpp), in the table's order.
    template <class Table>
    struct ArraysOf;
    template <class... Q>
    struct ArraysOf<std::tuple<Q...>> {
        using type = std::tuple<std::vector<typename Q::Value>...>;
    };
    using StateArrays = ArraysOf<std::remove_cv_t<decltype(kGrainQuantities)>>::type;
    static constexpr std::size_t kUid = grainQuantityIndex("uid");
    static constexpr std::size_t kPosition = grainQuantityIndex("position");
    static constexpr std::size_t kVelocity = grainQuantityIndex("velocity");
    static constexpr std::size_t kAngularVelocity = grainQuantityIndex("angular_velocity");
    static constexpr std::size_t kOrientation = grainQuantityIndex("orientation");
    static constexpr std::size_t kForce = grainQuantityIndex("force");
    static constexpr std::size_t kTorque = grainQuantityIndex("torque");
    static constexpr std::size_t kRadius = grainQuantityIndex("radius");
    static constexpr std::size_t kMass = grainQuantityIndex("mass");
    static constexpr std::size_t kType = grainQuantityIndex("type");
    static constexpr std::size_t kFlags = grainQuantityIndex("flags");
    template <std::size_t K>
    [[nodiscard]] std::vector<ValueOf<K>>& array() {
        return std::get<K>(m_state);
    }
    template <std::size_t K>
    [[nodiscard]] std::vector<ValueOf<K>> const& array() const {
        return std::get<K>(m_state);
    }

    void updateInverses(Index i);
    /// Gives every copy the identity orientation in array<kOrientation>() (capacity as the others).
    void storeOrientations();
    /// Calls `f` for every per-copy array (array<kOrientation>() only while it is stored).
    template <class F>
    void forEachArray(F&& f);
    /// Reads the key of a stored copy for m_index, which keeps no keys (see CopyIndex).
    [[nodiscard]] auto keyAt() const {
        return [this](std::uint32_t i) { return CopyKey{array<kUid>()[i], m_image[i]}; };
    }
    /// The slot of `owner` in m_owners, appended if new.
    [[nodiscard]] std::uint32_t ownerSlot(BlockRef const& owner);

    /// The table's arrays (GrainQuantities.hpp), one per entry; those kept Elsewhere stay empty,
    /// the orientation's (WhenNeeded) is empty while every copy has the identity.
    StateArrays m_state;
    // Derived from mass, radius and the Fixed flag (updateInverses).
    std::vector<double> m_invMass;
    std::vector<double> m_invInertia;
    // The owner block of each copy as a 4-byte slot in a table of the distinct owners seen
    // (12 bytes per copy less than a BlockRef): a block's copies have few owners, its own
    // block and the neighbours whose grains reach it. The table only grows (until clear()).
    std::vector<std::uint32_t> m_ownerSlot;
    std::vector<BlockRef> m_owners;
    std::uint32_t m_lastOwnerSlot = 0; ///< where the last look-up hit: most hit it again
    std::vector<CopyImage> m_image;
    std::vector<HolderList> m_shadowHolders;
    std::vector<ContactHistory> m_history;
    std::vector<std::uint32_t> m_historyOf;    ///< shareHistories(): per copy (empty: its own)
    std::vector<std::vector<double>> m_fields; ///< one array per declared grain-field component
    CopyIndex m_index;
    // Tracing (empty while off): tag per copy, slots written since the follower last looked.
    std::vector<std::uint32_t> m_traceTag;
    std::vector<TraceChange> m_traceJournal;
    core::Vec3 m_wrapPeriod = core::Vec3::Zero();
    std::uint64_t m_traceSession = 0;
    bool m_traceBroken = false;
    /// Gives the storage a layout revision no storage had before.
    void touchLayout() {
        if (!m_historyOf.empty())
            stopSharingHistories();
        m_layoutRevision = s_layoutRevisions.fetch_add(1) + 1;
    }
    static inline std::atomic<std::uint64_t> s_layoutRevisions{0};
    std::uint64_t m_layoutRevision = s_layoutRevisions.fetch_add(1) + 1;
};

} // namespace regolith::particles
