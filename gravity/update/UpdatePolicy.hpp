#pragma once
/// When to recompute self-gravity (issue 7; the second paper, §3 and §6: "self-gravity is
/// updated after at least one particle has moved more than a certain distance threshold",
/// there twice the largest radius). Between updates the grains keep the stored field.
#include "core/mpi/Comm.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>

namespace regolith::gravity {

class UpdatePolicy {
public:
    /// `threshold` in m (`gravity.update_threshold`); 0 recomputes every step. Throws
    /// core::InputError naming the key if negative or not finite.
    explicit UpdatePolicy(double threshold);

    /// True if gravity must be recomputed: no update yet, or some grain on some rank has
    /// moved more than the threshold since the last markUpdated() (global maximum), or a
    /// grain that was not on this rank at the last update is here now (it migrated: its
    /// displacement is unknown here, so the policy errs on the safe side). Positions in m,
    /// grains identified by `uid`. COLLECTIVE over `comm`.
    [[nodiscard]] bool due(core::Comm const& comm, std::span<std::uint64_t const> uid,
                           std::span<double const> x, std::span<double const> y,
                           std::span<double const> z);

    /// Records the positions of this rank's grains at an update and counts it. Not
    /// collective (call it on every rank after every update).
    void markUpdated(std::span<std::uint64_t const> uid, std::span<double const> x,
                     std::span<double const> y, std::span<double const> z);

    [[nodiscard]] long long updates() const { return m_updates; }
    [[nodiscard]] double threshold() const { return m_threshold; }
    /// The global largest displacement found by the last due(), m (not measured, so 0, with
    /// threshold 0: due() is then true at once, without communication).
    [[nodiscard]] double lastMaxDisplacement() const { return m_lastMax; }

    /// Empty if threshold <= spacing (m, the typical centre distance of neighbouring
    /// grains); else a warning that states the expected error: a neighbour at distance s
    /// displaced by δ changes its pull by up to ~2δ/s, so near-field forces may be off by
    /// that fraction before the next update.
    [[nodiscard]] static std::string thresholdWarning(double threshold, double spacing);

private:
    double m_threshold;
    long long m_updates = 0;
    double m_lastMax = 0.0;
    std::unordered_map<std::uint64_t, std::array<double, 3>> m_reference;
};

} // namespace regolith::gravity
