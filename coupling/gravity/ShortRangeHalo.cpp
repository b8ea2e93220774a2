#include "coupling/gravity/ShortRangeHalo.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace regolith::coupling {

namespace {

/// Squared gap between two closed boxes (0 if they touch or overlap).
double sqGap(core::AABB const& a, core::AABB const& b) {
    core::Vec3 const d = (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(core::Vec3::Zero());
    return d.squaredNorm();
}

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0)))
        --q;
    return q;
}

} // namespace

ShortRangeHalo::ShortRangeHalo(core::Comm const& comm, domain::BlockForest const& forest,
                               gravity::CellLayout const& layout, double cutoff)
    : m_forest(&forest)
    , m_cutoff(cutoff)
    , m_rank(comm.rank())
    , m_exchange(comm) {
    if (!(cutoff > 0.0) || !std::isfinite(cutoff))
        throw core::Error("ShortRangeHalo: the cut-off must be positive and finite");
    core::AABB const& domain = forest.domain();
    core::Vec3 const extent = domain.extent();
    auto const& roots = forest.rootBlocks();
    auto const& periodic = forest.periodic();
    auto const& cells = layout.cellsPerBlock();
    core::Vec3 edge;
    for (int a = 0; a < 3; ++a)
        edge[a] = extent[a] / roots[static_cast<std::size_t>(a)];
    for (domain::Block const& block : forest.blocks()) {
        std::vector<Image>& images = m_images.emplace_back();
        std::array<std::int64_t, 3> from{}, to{};
        for (int a = 0; a < 3; ++a) {
            auto const ua = static_cast<std::size_t>(a);
            from[ua] = static_cast<std::int64_t>(
                std::floor((block.aabb.min[a] - cutoff - domain.min[a]) / edge[a]));
            to[ua] = static_cast<std::int64_t>(
                std::floor((block.aabb.max[a] + cutoff - domain.min[a]) / edge[a]));
            if (!periodic[ua]) {
                from[ua] = std::max<std::int64_t>(from[ua], 0);
                to[ua] = std::min<std::int64_t>(to[ua], roots[ua] - 1);
            }
        }
        for (std::int64_t k = from[2]; k <= to[2]; ++k)
            for (std::int64_t j = from[1]; j <= to[1]; ++j)
                for (std::int64_t i = from[0]; i <= to[0]; ++i) {
                    std::array<std::int64_t, 3> const u{i, j, k};
                    gravity::GlobalCell corner{};
                    Image image;
                    for (std::size_t a = 0; a < 3; ++a) {
                        std::int64_t const image_ = floorDiv(u[a], roots[a]);
                        std::int64_t const w = u[a] - image_ * roots[a];
                        corner[a] = w * cells[a];
                        auto const ia = static_cast<int>(a);
                        image.shift[ia] = static_cast<double>(image_) * extent[ia];
                        image.box.min[ia] =
                            domain.min[ia] + static_cast<double>(w) * edge[ia] + image.shift[ia];
                        image.box.max[ia] = image.box.min[ia] + edge[ia];
                    }
                    auto const owner = layout.owner(corner);
                    if (!owner)
                        throw core::Error("ShortRangeHalo: a root block has no owner");
                    image.rank = owner->rank;
                    if (image.rank == m_rank && image.shift.isZero(0.0))
                        continue; // this rank's own grains are already local
                    if (sqGap(image.box, block.aabb) < cutoff * cutoff)
                        images.push_back(image);
                }
    }
}

void ShortRangeHalo::destinations(core::Vec3 const& x, int b) {
    m_found.clear();
    // The sender decides with a slightly longer reach than the pair test (|d| < cutoff), so
    // that rounding can add a halo grain, never lose one.
    double const reach = m_cutoff * (1.0 + 1e-12);
    auto visit = [&](std::vector<Image> const& images) {
        for (Image const& im : images) {
            if (!im.box.intersectsSphere(x, reach))
                continue;
            bool const seen = std::any_of(m_found.begin(), m_found.end(), [&](Image const* f) {
                return f->rank == im.rank && f->shift == im.shift;
            });
            if (!seen)
                m_found.push_back(&im);
        }
    };
    if (b >= 0) {
        visit(m_images[static_cast<std::size_t>(b)]);
    } else {
        for (auto const& images : m_images)
            visit(images);
    }
}

void ShortRangeHalo::gather(std::span<core::Vec3 const> position, std::span<double const> mass) {
    m_position.clear();
    m_mass.clear();
    m_sent = 0;
    auto const blocks = m_forest->blocks();
    for (std::size_t i = 0; i < position.size(); ++i) {
        core::Vec3 const& x = position[i];
        domain::Block const* block = m_forest->localBlockContaining(x);
        int b = -1;
        if (block != nullptr) {
            core::AABB const& box = block->aabb;
            bool const deepInside = ((x - box.min).array() >= m_cutoff).all() &&
                                    ((box.max - x).array() >= m_cutoff).all();
            if (deepInside)
                continue;
            b = static_cast<int>(block - blocks.data());
        }
        destinations(x, b);
        for (Image const* im : m_found) {
            core::Vec3 const there = x - im->shift; // the grain in the owner's frame
            if (im->rank == m_rank) {
                m_position.push_back(there);
                m_mass.push_back(mass[i]);
            } else {
                m_exchange.sendBuffer(im->rank) << there << mass[i];
                ++m_sent;
            }
        }
    }
    m_exchange.start();
    m_exchange.wait([&](int, core::RecvBuffer& in) {
        while (!in.exhausted()) {
            core::Vec3 p;
            double m = 0.0;
            in >> p >> m;
            m_position.push_back(p);
            m_mass.push_back(m);
        }
    });
}

} // namespace regolith::coupling
