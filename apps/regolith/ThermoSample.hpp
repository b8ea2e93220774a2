#pragma once
/// The run's physics every output.thermo_every steps, as LAMMPS's `thermo` prints it: energies,
/// momenta, contacts, the largest overlap and the walls' forces, measured over all ranks, and
/// the table of the columns thermo.csv and the standard-output lines show (one row per column:
/// its name, what it is, how it is printed and where its value comes from; a new quantity is
/// one more field and one more row).
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/storage/WallList.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace regolith::apps {

/// One measurement, the same on every rank.
struct ThermoSample {
    std::int64_t step = 0;
    double time = 0.0;
    double translationalEnergy = 0.0; ///< sum 1/2 m |v|^2
    double rotationalEnergy = 0.0;    ///< sum 1/2 I |w|^2, I = 2/5 m r^2
    double externalPotential = 0.0;   ///< sum -m g.x in gravity.external
    double selfPotential = 0.0;       ///< 1/2 sum m phi of the last self-gravity field
    core::Vec3 momentum = core::Vec3::Zero();
    core::Vec3 angularMomentum = core::Vec3::Zero(); ///< about the origin, spins included
    std::int64_t contacts = 0;                       ///< grain-grain and grain-wall contacts
    double maxOverlap = 0.0; ///< largest penetration / smaller radius (a wall's: / radius)
    std::int64_t grains = 0;
    double imbalance = 1.0; ///< the last measured max / mean load of the ranks
    /// Per wall ([[walls]] order): the force the grains exert on it in the last evaluation.
    std::vector<core::Vec3> wallForces;
};

/// What is measured besides the grains: where, gravity and the self-gravity energy.
struct ThermoContext {
    std::int64_t step = 0;
    double time = 0.0;
    core::Vec3 gravity = core::Vec3::Zero(); ///< gravity.external
    double selfPotential = 0.0;
    double imbalance = 1.0;
    particles::WallList const* walls = nullptr; ///< the run's walls (none: no wall columns)
};

/// Measures the masters of `local` and the contacts of the last force computation
/// (`contacts[b]` those of local block b, each contact in exactly one list: DemStep::contacts
/// with the pair contacts kept). Energies and momenta as conservedQuantities computes them.
/// COLLECTIVE over `comm`.
[[nodiscard]] ThermoSample measureThermo(core::Comm const& comm,
                                         particles::LocalParticles const& local,
                                         std::span<particles::ContactList const> contacts,
                                         ThermoContext const& context);

/// One column of thermo.csv: its header name, a description (docs/guide/run-summary.md) and
/// its value; integer columns are printed without a fraction.
struct ThermoColumn {
    std::string name;
    std::string description;
    bool integer = false;
    std::function<double(ThermoSample const&)> value;
};

/// The columns in order: the run's quantities, then wall<k>_fx, _fy, _fz for each of `walls`
/// walls.
[[nodiscard]] std::vector<ThermoColumn> thermoColumns(std::size_t walls);

} // namespace regolith::apps
