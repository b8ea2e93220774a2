#pragma once
/// The run summary every app writes with `--json` (docs/design.md, "Run summary").
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace regolith::apps {

/// The summary object; every key of the contract is always present. Times in seconds.
struct RunSummary {
    std::string scene;
    int ranks = 1;
    std::int64_t blocks = 0;
    /// The particles' subdomains over all ranks and how they were cut (JSON keys
    /// "particle_subdomains" and "subdomains": "merged" or "blocks", beyond the contract's).
    std::int64_t particleSubdomains = 0;
    std::string subdomains;
    std::string sync;
    std::int64_t particles = 0; ///< masters at the end, over all ranks
    std::int64_t shadows = 0;   ///< shadow copies at the end, over all ranks
    /// Masters removed during the run because they left a non-periodic domain, over all
    /// ranks (JSON key "left_domain", beyond the contract's keys).
    std::int64_t leftDomain = 0;
    /// Of those, the masters that passed through a wall, over all ranks (JSON key
    /// "left_through_walls", beyond the contract's keys).
    std::int64_t leftThroughWalls = 0;
    /// Grains the [[insert]] entries added during this invocation, over all ranks (JSON key
    /// "inserted", beyond the contract's keys).
    std::int64_t inserted = 0;
    std::int64_t steps = 0;
    double wallSeconds = 0.0; ///< the time-step loop only (set-up and output excluded)
    std::uint64_t peakRssBytes = 0;

    struct Timing {
        double sync = 0.0;
        double contact = 0.0;
        double gravity = 0.0;
        double integrate = 0.0;
    } timing;

    /// Self-gravity (JSON key "gravity", beyond the contract's keys): the method, how often
    /// the field was computed (update policy, gravity.update_threshold) and the force error
    /// measured during the run (gravity.check_every; JSON "error": checks, samples, median,
    /// p99, max; all 0 without checks).
    struct Gravity {
        std::string method = "none";
        long long updates = 0;
        long long interval = 0; ///< gravity.update_every at the end [steps] (JSON "interval")
        long long checks = 0;
        long long samples = 0;
        double medianError = 0.0;
        double p99Error = 0.0;
        double maxError = 0.0;
    } gravity;

    /// The ranks' load balance (JSON key "balance", beyond the contract's keys): the
    /// imbalance max / mean of the ranks' loads (grains, contacts and grid cells of their
    /// blocks), averaged over the loop's steps (each measurement standing for the steps since
    /// the one before) and at its end, and the rebalances
    /// ([balance] every, threshold) with the time they took; "history": every measurement, the
    /// step after which it was taken and the imbalance then (before a rebalance).
    struct Balance {
        std::int64_t every = 0;
        double threshold = 1.1;
        long long rebalances = 0;
        long long splits = 0; ///< blocks split into eight (balance.split_levels)
        double seconds = 0.0;
        double meanImbalance = 1.0;
        double finalImbalance = 1.0;
        /// The heaviest block over a rank's mean load, the largest measured (after the
        /// blocks split): no cut of whole blocks brings the imbalance below it.
        double blockFloor = 1.0;
        std::vector<double> steps;
        std::vector<double> imbalances;
    } balance;

    /// The "auto" scene keys and what was chosen (JSON key "auto": {key: {value, reason}},
    /// beyond the contract's keys).
    struct AutoChoice {
        std::string key, value, reason;
    };
    std::vector<AutoChoice> autoChoices;

    /// The contact detection's Verlet lists (JSON key "neighbour_list", beyond the contract's
    /// keys): the largest skin of the blocks' last rebuilds (0: no list, contact.neighbour_skin
    /// = 0), the rebuilds during the loop and the shifts with the grains' drift that took a
    /// rebuild's place, over all blocks and ranks.
    struct NeighbourList {
        double skin = 0.0;
        std::int64_t rebuilds = 0;
        std::int64_t shifts = 0;
    } neighbourList;

    struct Communication {
        double messagesPerStep = 0.0;
        double bytesPerStep = 0.0;
        int maxPeers = 0;
    } comm;

    struct Conserved {
        core::Vec3 momentum = core::Vec3::Zero();
        core::Vec3 angularMomentum = core::Vec3::Zero();
        double kineticEnergy = 0.0; ///< translational and rotational
        /// Of kinetic_energy, the rotational part sum 1/2 I |w|^2 (JSON key
        /// "rotational_kinetic_energy", beyond the contract).
        double rotationalEnergy = 0.0;
        double potentialEnergy = 0.0;
        core::Vec3 centerOfMass = core::Vec3::Zero();
        double mass = 0.0; ///< total mass of the masters (beyond the contract)
    } conserved;
    /// The same at the loop's start (JSON key "conserved_initial"; a restart's: the
    /// checkpoint's state), and the simulated time at the end (JSON key "time").
    Conserved initialConserved;
    double time = 0.0;

    /// What the grains did to each wall at the end and the work each wall did on them (JSON key
    /// "walls", an array in [[walls]] order, beyond the contract's keys), over all ranks.
    struct Wall {
        core::Vec3 force = core::Vec3::Zero();  ///< contact force on the wall, last step
        core::Vec3 torque = core::Vec3::Zero(); ///< about its axis point, last step
        double work = 0.0;                      ///< done on the grains during this invocation
    };
    std::vector<Wall> walls;

    std::string checksum; ///< hex digest of the uid-sorted final state
};

/// Particle updates per core-second: steps * particles / (wall_s * ranks); 0 when nothing
/// was timed (wall_s <= 0), so the JSON never holds an infinity.
[[nodiscard]] double pupcs(RunSummary const& s);

/// The summary as a JSON document (keys in the order of docs/design.md, "Run summary";
/// "left_domain" follows "shadows").
[[nodiscard]] std::string toJson(RunSummary const& s);

/// The largest peak resident set size of any rank, in bytes (getrusage ru_maxrss, which
/// Linux reports in KiB). COLLECTIVE over `comm`.
[[nodiscard]] std::uint64_t peakRssBytes(core::Comm const& comm);

} // namespace regolith::apps
