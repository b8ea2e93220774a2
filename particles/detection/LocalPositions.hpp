#pragma once
/// The local positions of a storage's copies (x + image * period, CopyImage.hpp's
/// localPosition) as an array computed on access: contact detection bins and tests them a few
/// times per rebuild, and a copy of them cost 24 bytes per copy at the run's peak.
#include "core/math/Vec3.hpp"
#include "particles/storage/CopyImage.hpp"

#include <cstddef>
#include <span>

namespace regolith::particles {

class LocalPositions {
public:
    /// Positions used as they are.
    explicit LocalPositions(std::span<core::Vec3 const> positions)
        : m_x(positions) {}
    /// Canonical positions shifted by their images (one per position) times `period`.
    LocalPositions(std::span<core::Vec3 const> canonical, std::span<CopyImage const> images,
                   core::Vec3 const& period)
        : m_x(canonical)
        , m_image(images)
        , m_period(period) {}

    [[nodiscard]] std::size_t size() const { return m_x.size(); }
    /// Same bits as localPosition(canonical[k], images[k], period).
    [[nodiscard]] core::Vec3 operator[](std::size_t k) const {
        return m_image.empty() ? m_x[k] : localPosition(m_x[k], m_image[k], m_period);
    }

private:
    std::span<core::Vec3 const> m_x;
    std::span<CopyImage const> m_image; ///< empty: no shift
    core::Vec3 m_period = core::Vec3::Zero();
};

} // namespace regolith::particles
