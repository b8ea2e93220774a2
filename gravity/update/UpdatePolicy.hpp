#pragma once
/// When to recompute self-gravity (the second paper, §3 and §6: "self-gravity is
/// updated after at least one particle has moved more than a certain distance threshold",
/// there twice the largest radius). Between updates the grains keep the stored field.
///
/// The decision depends on the grains only, not on the ranks or blocks that hold them: a
/// grain that changed rank since the last update brings its record (position and field at
/// the update) along (GrainRecordExchange.hpp), so with a deterministic evaluator the update
/// steps, and hence the trajectories, are the same on any layout (reproducible mode).
#include "core/mpi/Comm.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace regolith::core {
class SparseExchange;
}

namespace regolith::gravity {

/// What the policy remembers of one grain from the last update.
struct GrainRecord {
    std::array<double, 3> reference{}; ///< position at the last update [length]
    std::array<double, 3> field{};     ///< acceleration computed then [m s^-2]
    /// With an update interval: the field's rate of change between the grain's last two
    /// updates [m s^-3] (0 after its first), which extrapolates it until the next.
    std::array<double, 3> slope{};
};

/// Updates by the step count (`gravity.update_every`), besides or instead of the displacement
/// threshold. Between updates each grain's field is extrapolated linearly in time from its last
/// two updates, a(t) = a_k + (a_k - a_{k-1}) (t - t_k) / (t_k - t_{k-1}): the field of a body
/// moving or turning as a whole follows it to first order, where the kept field lags by the
/// whole motion. Adaptive: after every update the interval is scaled so that the median
/// relative error of that prediction against the new field, over a sample of grains picked by
/// uid, meets `budget` (error ∝ interval² once the slopes are known, ∝ interval before).
struct UpdateInterval {
    long long every = 0;       ///< steps between updates; 0: the threshold alone decides
    bool adaptive = false;     ///< `every` is the first interval and then adapts
    double budget = 0.0;       ///< adaptive: the median prediction error aimed at
    double dt = 0.0;           ///< time step [s] (slopes are per unit time; > 0 with every > 0)
    long long maxEvery = 1000; ///< adaptive: the longest interval [steps]
    std::size_t sample = 1000; ///< adaptive: grains judged per update, over all ranks
};

class UpdatePolicy {
public:
    /// `threshold` in m (`gravity.update_threshold`); 0 recomputes every step. Throws
    /// core::InputError naming the key if negative or not finite. `period`: the domain's
    /// extent on its periodic axes, 0 on the others; a displacement is measured to the nearest
    /// image there, so that a grain wrapped across a periodic face has moved only its step
    /// (not the jump across the domain, which would count an update at every crossing).
    /// `interval`: updates by the step count too (UpdateInterval); its `every` < 0, an adaptive
    /// one without a budget in (0, 1), or a dt <= 0 throw core::InputError naming
    /// gravity.update_every.
    explicit UpdatePolicy(double threshold, std::array<double, 3> period = {0.0, 0.0, 0.0},
                          UpdateInterval interval = {});
    ~UpdatePolicy();
    UpdatePolicy(UpdatePolicy&&) noexcept;
    UpdatePolicy& operator=(UpdatePolicy&&) noexcept;

    /// True if gravity must be recomputed: no update yet, or some grain on some rank has
    /// moved more than the threshold since the last markUpdated() (global maximum), or the
    /// interval's steps have passed, or a grain has no record on any rank (it did not exist at
    /// the last update). Records of
    /// grains that arrived from another rank are fetched from there first (one sparse
    /// exchange through a directory rank, only on steps where some grain arrived; records no
    /// local grain claims are given away then). Positions in m, grains identified by `uid`.
    /// COLLECTIVE over `comm` (the same communicator at every call).
    [[nodiscard]] bool due(core::Comm const& comm, std::span<std::uint64_t const> uid,
                           std::span<double const> x, std::span<double const> y,
                           std::span<double const> z);
    /// due() in two parts, for a caller that reduces the verdict together with its own (one
    /// reduction fewer per step): localVerdict() measures this rank's grains (the largest
    /// displacement, +inf before the first update; 1 if a grain has no record here, else 0)
    /// and is not collective; decideDue() takes the element-wise maximum of every rank's
    /// verdict and the same grains, and is COLLECTIVE only when some rank misses a record.
    /// due() is localVerdict, an all-reduce and decideDue.
    [[nodiscard]] std::array<double, 2> localVerdict(std::span<std::uint64_t const> uid,
                                                     std::span<double const> x,
                                                     std::span<double const> y,
                                                     std::span<double const> z);
    [[nodiscard]] bool decideDue(core::Comm const& comm, std::array<double, 2> global,
                                 std::span<std::uint64_t const> uid, std::span<double const> x,
                                 std::span<double const> y, std::span<double const> z);

    /// Records the positions of this rank's grains at an update and counts it. Not
    /// collective (call it on every rank after every update).
    void markUpdated(std::span<std::uint64_t const> uid, std::span<double const> x,
                     std::span<double const> y, std::span<double const> z);
    /// As above, also keeping each grain's field (ax, ay, az) for the steps until the next
    /// update (record()).
    void markUpdated(std::span<std::uint64_t const> uid, std::span<double const> x,
                     std::span<double const> y, std::span<double const> z,
                     std::span<double const> ax, std::span<double const> ay,
                     std::span<double const> az);

    /// With an adaptive interval, after markUpdated() on every rank: scales the interval by
    /// the prediction errors measured there (UpdateInterval). COLLECTIVE over `comm`.
    void adaptInterval(core::Comm const& comm);

    /// The record of grain `uid` on this rank, or nullptr. After a due() that returned
    /// false, every grain passed to it has one. Not collective.
    [[nodiscard]] GrainRecord const* record(std::uint64_t uid) const;
    /// The field of the i-th grain passed to the last due() that returned false, at this step:
    /// its field at the last update extrapolated with its slope over the steps since (the kept
    /// field without an interval); from a copy of the records in that order, read without
    /// lookups. Not collective.
    [[nodiscard]] std::array<double, 3> fieldAt(std::size_t i) const;
    /// fieldAt() of every grain passed to that due(), in its order, into `x`, `y`, `z` (one
    /// value per grain each): the same values in one pass over the copied records, as the
    /// coupled step applies them. Not collective.
    void fieldsAt(std::span<double> x, std::span<double> y, std::span<double> z) const;

    /// Continues from a checkpoint: `updates` as updates(), and records of any grains (not
    /// necessarily this rank's: the next due() brings each to the rank holding its grain).
    /// Records with a non-finite reference are skipped (that grain counts as new); with
    /// threshold 0 all are ignored. Not collective.
    void restore(long long updates, std::span<std::uint64_t const> uid,
                 std::span<GrainRecord const> records);
    /// Continues the interval from a checkpoint: steps since the last update and the current
    /// interval (stepsSinceUpdate(), interval()). Not collective.
    void restoreInterval(long long sinceUpdate, long long every);

    [[nodiscard]] long long updates() const { return m_updates; }
    [[nodiscard]] long long stepsSinceUpdate() const { return m_since; }
    /// The current interval in steps (0 without one).
    [[nodiscard]] long long interval() const { return m_every; }
    /// The median prediction error the last adaptInterval() measured (0 before).
    [[nodiscard]] double lastPredictionError() const { return m_lastPredictionError; }
    [[nodiscard]] double threshold() const { return m_threshold; }
    /// The global largest displacement found by the last due(), m (not measured, so 0, with
    /// threshold 0: due() is then true at once, without communication).
    [[nodiscard]] double lastMaxDisplacement() const { return m_lastMax; }

    /// Empty if threshold <= spacing (m, the typical centre distance of neighbouring
    /// grains); else a warning that states the expected error: a neighbour at distance s
    /// displaced by δ changes its pull by up to ~2δ/s, so near-field forces may be off by
    /// that fraction before the next update.
    [[nodiscard]] static std::string thresholdWarning(double threshold, double spacing);

    /// A record and the due() call that last found its grain here.
    struct Entry {
        GrainRecord record;
        std::uint64_t seen = 0;
    };

private:
    /// Records kept between updates (threshold or interval), else every step is an update.
    [[nodiscard]] bool keepsRecords() const { return m_threshold > 0.0 || m_every > 0; }
    /// The time the fields are extrapolated over (0 without an interval: the kept field) [s].
    [[nodiscard]] double sinceUpdateSeconds() const;

    double m_threshold;
    UpdateInterval m_interval;
    long long m_every = 0; ///< the current interval [steps]
    long long m_since = 0; ///< due() calls since the last update
    double m_lastPredictionError = 0.0;
    /// markUpdated's prediction errors of the grains here, with their uids (adaptInterval).
    std::vector<std::uint64_t> m_judgedUid;
    std::vector<double> m_judgedError;
    std::array<double, 3> m_period; ///< periodic extents, 0 on open axes [length]
    long long m_updates = 0;
    double m_lastMax = 0.0;
    std::uint64_t m_call = 0; ///< due() calls so far (Entry::seen)
    std::unordered_map<std::uint64_t, Entry> m_records;
    /// The last due()'s grains and their entries (stable in the map until it is rebuilt): a
    /// step whose grains are the same, in the same order, as the last one's (most steps) finds
    /// them without hashing.
    std::vector<std::uint64_t> m_foundUid;
    std::vector<Entry*> m_found;
    /// Forgets the records found for the grains of the last due(), whose entries moved or
    /// went: both lists, so that a rank left without grains holds no pointer either.
    void forgetFound() {
        m_foundUid.clear();
        m_found.clear();
    }
    std::vector<double> m_atField, m_atSlope; ///< their fields and slopes, 3 per grain
    // Between localVerdict() and decideDue():
    std::vector<std::size_t> m_missing; ///< grains without a record here (they changed rank)
    double m_localMax = 0.0;            ///< the largest displacement here
    bool m_lookedUp = false;            ///< the records were looked up (not the last ones')
    std::unique_ptr<core::SparseExchange> m_exchange; ///< made at the first migration
};

} // namespace regolith::gravity
