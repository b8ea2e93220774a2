#pragma once
/// The periodic frame contact detection works in: the domain box, which axes wrap, and the
/// one rule (domain::ForestGeometry's) that maps a point to its domain image.
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"
#include "particles/storage/CopyImage.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace regolith::domain {
class BlockForest;
class ForestGeometry;
} // namespace regolith::domain

namespace regolith::particles {

/// The domain and its periodic axes as contact detection sees them. A default-constructed
/// frame is non-periodic and infinite: every point is in image 0 and `wrap` is the identity.
struct PeriodicFrame {
    /// The whole domain (not a block) [length]; only its periodic axes matter, and those must
    /// be finite with max > min.
    core::AABB domain{core::Vec3::Constant(-std::numeric_limits<double>::infinity()),
                      core::Vec3::Constant(std::numeric_limits<double>::infinity())};
    std::array<bool, 3> periodic{false, false, false};
    /// Periodic axes the detecting storage spans and holds no image on: its pairs across
    /// those faces are found through cells that wrap, each with its shift (LinkedCells), and
    /// the contact-point rule does not look at them (one instance per pair).
    std::array<bool, 3> wrapped{false, false, false};

    /// Non-periodic and infinite.
    PeriodicFrame() = default;
    /// `domain` with the periodic axes `periodic` (their extent must be finite and > 0).
    PeriodicFrame(core::AABB const& domainBox, std::array<bool, 3> periodicAxes)
        : domain(domainBox)
        , periodic(periodicAxes) {}
    /// The frame of a block forest's geometry: its domain and periodicity, no axis wrapped
    /// (for copies at every image; the particles of a BlockForest use the constructor below).
    explicit PeriodicFrame(domain::ForestGeometry const& geometry);
    /// The frame the particles of `forest` are detected in: wrappedAxes(forest) wrap.
    explicit PeriodicFrame(domain::BlockForest const& forest);

    /// Domain extent on periodic axes, 0 on the others [length] (the `period` of
    /// CopyImage.hpp's imageOffset / localPosition).
    [[nodiscard]] core::Vec3 period() const;
    /// period() on the wrapped axes, 0 on the others (ParticleStorage::wrapPeriod).
    [[nodiscard]] core::Vec3 wrapPeriod() const;
    [[nodiscard]] bool anyPeriodic() const { return periodic[0] || periodic[1] || periodic[2]; }
    [[nodiscard]] bool anyWrapped() const { return wrapped[0] || wrapped[1] || wrapped[2]; }

    /// (w, o) with w in [min, max) on every periodic axis (p unchanged on the others) and
    /// p ~ w + o * extent, o = 0 on non-periodic axes. The image is decided against the
    /// boundaries min + o * extent and w is clamped so it never equals max: domain::wrapOnAxis
    /// on each periodic axis, the rule of ForestGeometry::locate / wrap (one implementation).
    /// Points already inside the domain on every periodic axis are returned as they are, image 0
    /// (as ForestGeometry does). Throws core::Error if p is not finite on a periodic axis or
    /// the image lies beyond +-kMaxImage periods.
    [[nodiscard]] std::pair<core::Vec3, CopyImage> wrap(core::Vec3 const& p) const {
        // The common case inline: inside on every periodic axis (ForestGeometry answers image
        // 0 and p itself there too).
        for (std::size_t a = 0; a < 3; ++a)
            if (periodic[a] && !(p[static_cast<int>(a)] >= domain.min[static_cast<int>(a)] &&
                                 p[static_cast<int>(a)] < domain.max[static_cast<int>(a)]))
                return wrapOutside(p);
        return {p, kNoImage};
    }

    /// Calls f(shift) for every shift s (whole periods on the wrapped axes, 0 on the others)
    /// with |d_a - s_a * period_a| <= reach on each wrapped axis: the images of a point at
    /// x - d from x that may lie within `reach` of x.
    template <class F>
    void forEachWrappedImage(core::Vec3 const& d, double reach, F&& f) const {
        std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
        core::Vec3 const p = period();
        for (std::size_t a = 0; a < 3; ++a)
            if (wrapped[a]) {
                double const e = p[static_cast<int>(a)];
                lo[a] = static_cast<int>(std::ceil((d[static_cast<int>(a)] - reach) / e));
                hi[a] = static_cast<int>(std::floor((d[static_cast<int>(a)] + reach) / e));
            }
        for (int i = lo[0]; i <= hi[0]; ++i)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int k = lo[2]; k <= hi[2]; ++k)
                    f(CopyImage{static_cast<std::int8_t>(i), static_cast<std::int8_t>(j),
                                static_cast<std::int8_t>(k)});
    }

private:
    [[nodiscard]] std::pair<core::Vec3, CopyImage> wrapOutside(core::Vec3 const& p) const;

public:
};

/// The periodic axes along which the particles of `forest` hold no periodic images: the pairs
/// across those faces are found by cells that wrap (PeriodicFrame::wrapped), and the
/// synchronisation makes no copy through them. Those that every subdomain spans (one
/// subdomain spans every axis; slabs span the axes they are not cut along).
[[nodiscard]] std::array<bool, 3> wrappedAxes(domain::BlockForest const& forest);

} // namespace regolith::particles
