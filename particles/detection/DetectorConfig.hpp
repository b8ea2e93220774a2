#pragma once
/// What configures contact detection and what one detection call reports (ContactDetector).
#include <cstddef>

namespace regolith::particles {

struct DetectorConfig {
    /// Verlet skin [length]: with skin > 0 (or relativeSkin > 0), detect() on a mutable
    /// storage keeps a neighbour list of the pairs closer than r_a + r_b + skin and reuses it
    /// until some copy moved skin / 2 (see ContactDetector). 0: linked cells every call.
    double skin = 0.0;
    /// If skin is 0: skin = relativeSkin * (the largest small radius) at every rebuild.
    double relativeSkin = 0.0;
    /// With relativeSkin: the list's skin may widen to 2, 3, ... times relativeSkin, up to
    /// this, where that lists hardly more pairs (a packing whose next neighbours lie beyond
    /// the first shell): the list then holds longer at nearly the same cost per step
    /// (ContactDetector, "A skin for the scene"). 0 or below relativeSkin: never wider.
    double widestRelativeSkin = 0.0;
    /// Spheres with a radius above this go to the large pass [length]; 0 = automatic:
    /// `largeFactor` times the median radius of the block's spheres.
    double largeRadius = 0.0;
    double largeFactor = 2.0;
    /// The cell grid has at most this many cells per small sphere (the edge grows otherwise).
    std::size_t maxCellsPerSphere = 8;
    /// Sort the output by (uid_i, uid_j, image(j) - image(i)) and (uid, wall), so that forces
    /// are summed in an order independent of storage order (reproducible mode). Costs
    /// O(C log C).
    bool sortByUid = false;
    /// Keep the tangential springs of the settled pairs deep inside the block beside the
    /// Verlet list (ContactDetector, "Springs kept beside the list") during the passes whose
    /// callback takes them (TakesKeptSprings). That caller must write them back
    /// (ContactDetector::beforeSync, writeBackSprings) before anything reads the histories.
    bool keepSprings = false;
    /// The contact model's interaction range [length] (AnyContactModel::interactionRange):
    /// pairs up to this gap apart are contacts too (penetration -gap), for a model that acts
    /// before grains touch (cohesion). Every candidate search, the Verlet list and the
    /// ownership settled for a list's life reach this much beyond r_a + r_b. Wall contacts
    /// stay overlaps. 0: overlaps only.
    double range = 0.0;
};

/// What the last `detect` call did (for tests and benchmarks).
struct DetectorStats {
    std::size_t smallSpheres = 0;
    std::size_t largeSpheres = 0;
    double largeThreshold = 0.0; ///< radius above which a sphere was large
    double cellEdge = 0.0;
    std::size_t cells = 0;
    std::size_t largeCellVisits = 0; ///< cells visited by the large pass in total
    std::size_t largeCandidates = 0; ///< sphere pairs the large pass tested
    /// Overlaps (Fixed pairs too) before the ownership rule, every image instance counted.
    /// Through the Verlet list, the pairs dropped at listing time because another block or
    /// image instance evaluates them for the list's whole life are not counted.
    std::size_t overlapsFound = 0;
    /// Spread of the candidate tests beyond r_a + r_b, against rounding of local positions.
    double slack = 0.0;
    /// Verlet list (mutable detect with a skin): the skin of the last rebuild, whether this
    /// call rebuilt, the pairs listed, the copies that arrived since the last rebuild and
    /// were added to the list in this call.
    double skin = 0.0;
    bool rebuilt = false;
    /// Shifts of the list with the copies' drift since the last detect (ContactDetector,
    /// "A list that follows a drift").
    std::uint32_t shifts = 0;
    std::size_t listedPairs = 0;
    /// Listed pairs whose contact this block evaluates whenever they overlap, decided when
    /// they were listed (no contact-point rule per step; see ContactDetector, "Verlet list").
    std::size_t settledPairs = 0;
    /// Of those, the pairs whose tangential spring is kept beside the list
    /// (DetectorConfig::keepSprings).
    std::size_t keptPairs = 0;
    /// Of those, the pairs handed on untested while the list holds (PairMode::KeptPressed).
    std::size_t pressedPairs = 0;
    std::size_t arrivals = 0;
};

} // namespace regolith::particles
