#pragma once
/// The reference scenes of Eibl & Rüde (2018), Table 1, as expansions of an app section of the
/// scene into the generic keys ([domain], [[particles]], [[walls]], [gravity]) before the
/// scene is read. Each app embeds its scene file (scenes/<app>.toml) and calls its expansion;
/// `--set <section>.<key>=...` changes the scenario (scaling, boxes, blocks per rank, radii).
///
/// The expansion owns domain.max and domain.blocks: a scene that sets them itself is refused
/// (InputError naming the key and the scenario keys to use instead). Every expansion is a
/// no-op when its section is absent, so a plain scene file runs unchanged. Not collective
/// (every rank computes the same from the same text).
#include "core/config/ConfigTable.hpp"

namespace regolith::apps {

/// [granular_gas] (the paper's "sparse" scenario): scaling = "weak" (default) lays a box of
/// `per_rank` (default [20, 20, 20]) per rank on the 3-D rank grid; "strong" uses the fixed
/// `box`. blocks = rank grid x `blocks_per_rank` (default [1, 1, 1]). The lattice fills the
/// domain.
void expandGranularGas(core::ConfigTable& scene, int ranks);

/// [dense_ramp] (the paper's "dense" scenario): as granular_gas on a 2-D rank grid (x, y);
/// per_rank default [20, 10 sqrt(3), 8] (20 hcp rows, so the y period fits the lattice);
/// the top wall ([[walls]] index 1) is put at the height; gravity of magnitude `gravity`
/// (default 1) tilted by `inclination` degrees (default 30) about y, pointing down the ramp
/// (+x).
void expandDenseRamp(core::ConfigTable& scene, int ranks);

/// [bidisperse] (the paper's "large" scenario): `building_blocks` = [nx, ny, nz] cubes of
/// edge `edge` (default 80), each cut into `blocks_per_building_block` (default [4, 4, 4])
/// blocks, each with one sphere of radius `large_radius` (default 15) at its centre
/// ([[particles]] index 0, a list), the small grains of the lattice entry around them.
void expandBidisperse(core::ConfigTable& scene, int ranks);

/// All of the above, in that order (what `regolith` and every app do first).
void expandScenarios(core::ConfigTable& scene, int ranks);

} // namespace regolith::apps
