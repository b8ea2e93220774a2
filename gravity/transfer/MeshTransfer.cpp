#include "gravity/transfer/MeshTransfer.hpp"

#include "core/Error.hpp"
#include "core/mpi/AgreeOnInputError.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

namespace regolith::gravity {

namespace {

std::string str(core::Vec3 const& v) {
    return fmt::format("[{}, {}, {}]", v[0], v[1], v[2]);
}

} // namespace

MeshTransfer::MeshTransfer(core::Comm const& comm, CellLayout const& layout, Assignment scheme)
    : m_comm(comm.duplicate())
    , m_layout(&layout)
    , m_scheme(scheme)
    , m_exchange(std::make_unique<core::SparseExchange>(m_comm)) {}

MeshTransfer::~MeshTransfer() = default;

template <class Visit>
bool MeshTransfer::visitInOneBlock(std::array<Stencil1D, 3> const& s, double sampleWeight,
                                   Visit& visit) const {
    // The common case: the whole stencil inside one block, no wrapping. One owner() lookup
    // (integer divisions) for the stencil, then index arithmetic: the lookups per cell were
    // most of the transfer's time.
    auto const& n = m_layout->cellsPerBlock();
    auto const& global = m_layout->globalCells();
    for (std::size_t a = 0; a < 3; ++a) {
        std::int64_t const first = s[a].first;
        std::int64_t const last = first + s[a].count - 1;
        if (first < 0 || last >= global[a] || first / n[a] != last / n[a])
            return false;
    }
    auto const base = m_layout->owner({s[0].first, s[1].first, s[2].first});
    if (!base)
        return false;
    auto const n0 = static_cast<std::size_t>(n[0]);
    auto const n1 = static_cast<std::size_t>(n[1]);
    auto const p0 = static_cast<std::size_t>(m_layout->padded()[0]);
    auto const p1 = static_cast<std::size_t>(m_layout->padded()[1]);
    CellOwner o = *base;
    for (int c = 0; c < s[2].count; ++c)
        for (int b = 0; b < s[1].count; ++b)
            for (int a = 0; a < s[0].count; ++a) {
                auto const ua = static_cast<std::size_t>(a);
                auto const ub = static_cast<std::size_t>(b);
                auto const uc = static_cast<std::size_t>(c);
                std::size_t const d = ua + n0 * (ub + n1 * uc);
                o.interior = base->interior + d;
                o.row = base->row + static_cast<std::int64_t>(d);
                o.pad = base->pad + ua + p0 * (ub + p1 * uc);
                visit(o, sampleWeight * s[0].w[ua] * s[1].w[ub] * s[2].w[uc]);
            }
    return true;
}

template <class Visit>
bool MeshTransfer::forEachCell(Grains const& grains, std::size_t i, Visit&& visit) {
    double const r = grains.radius.empty() ? 0.0 : grains.radius[i];
    ballSamples(r, m_layout->spacing(), m_samples);
    double const sampleWeight = 1.0 / static_cast<double>(m_samples.size());
    for (auto const& offset : m_samples) {
        core::Vec3 const u = m_layout->cellCoordinate(grains.position[i] + offset);
        std::array<Stencil1D, 3> const s{stencil(m_scheme, u[0]), stencil(m_scheme, u[1]),
                                         stencil(m_scheme, u[2])};
        if (visitInOneBlock(s, sampleWeight, visit))
            continue;
        for (int c = 0; c < s[2].count; ++c)
            for (int b = 0; b < s[1].count; ++b)
                for (int a = 0; a < s[0].count; ++a) {
                    double const w = sampleWeight * s[0].w[static_cast<std::size_t>(a)] *
                                     s[1].w[static_cast<std::size_t>(b)] *
                                     s[2].w[static_cast<std::size_t>(c)];
                    auto const owner =
                        m_layout->owner({s[0].first + a, s[1].first + b, s[2].first + c});
                    if (!owner) {
                        // A zero weight (a point exactly on a cell centre for CIC) outside
                        // the domain carries no mass: only refuse real losses.
                        if (w == 0.0)
                            continue;
                        return false;
                    }
                    visit(*owner, w);
                }
    }
    return true;
}

void MeshTransfer::agree(std::string const& error) const {
    // The lowest failing rank's message on every rank (rank 0 prints it).
    core::agreeOnInputError(m_comm, [&] {
        if (!error.empty())
            throw core::InputError(error);
    });
}

namespace {

std::string checkGrain(Grains const& g, std::size_t i, domain::BlockForest const& forest) {
    core::Vec3 const& p = g.position[i];
    double const r = g.radius.empty() ? 0.0 : g.radius[i];
    double const m = g.mass.empty() ? 0.0 : g.mass[i];
    if (!p.allFinite() || !std::isfinite(r) || r < 0.0 || !std::isfinite(m))
        return fmt::format("grid gravity: a grain has position {}, radius {}, mass {}: expected "
                           "finite values and radius >= 0",
                           str(p), r, m);
    if (!forest.insideDomain(p))
        return fmt::format("grid gravity: a grain at {} lies outside the domain {} - {}, which "
                           "the grid must hold (the particle methods drop such grains; enlarge the "
                           "domain)",
                           str(p), str(forest.domain().min), str(forest.domain().max));
    return {};
}

/// Why grain i's deposit (or interpolation) left the grid: its stencil of cells of edge h
/// reaches past an open face. Names how far inside the grain is, in cells, so that the cell size
/// shows as a cause as much as the domain (a grain far inside a grid of few, large cells).
std::string outside(Grains const& g, std::size_t i, domain::BlockForest const& forest,
                    core::Vec3 const& h) {
    core::Vec3 const& p = g.position[i];
    core::AABB const& box = forest.domain();
    double inside = std::numeric_limits<double>::infinity(); // in cells, to the nearest open face
    for (int a = 0; a < 3; ++a)
        if (!forest.periodic()[static_cast<std::size_t>(a)])
            inside = std::min(inside, std::min(p[a] - box.min[a], box.max[a] - p[a]) / h[a]);
    return fmt::format("grid gravity: a grain at {}{} puts mass outside the domain {} - {}: it "
                       "is {:.3g} cells (of edge {}) inside the nearest open face, and its "
                       "deposit stencil reaches past it; the grid methods need the grains about "
                       "two cells inside an open face: enlarge the domain, use more cells "
                       "(domain.cells_per_block), a periodic domain, or a particle method "
                       "(\"tree\", \"direct\"), which drops grains that leave",
                       str(p),
                       g.radius.empty() ? std::string(" (deposited as a point)")
                                        : fmt::format(" with radius {}", g.radius[i]),
                       str(box.min), str(box.max), inside, str(h));
}

} // namespace

void MeshTransfer::deposit(Grains const& grains, CellField& density) {
    auto const& forest = m_layout->forest();
    if (grains.mass.size() != grains.position.size() ||
        (!grains.radius.empty() && grains.radius.size() != grains.position.size()))
        throw core::Error("MeshTransfer::deposit: position, radius and mass spans differ in size");
    double const invVolume = 1.0 / m_layout->cellVolume();
    std::map<int, std::unordered_map<std::int64_t, double>> remote;
    std::string error;
    for (std::size_t i = 0; i < grains.position.size() && error.empty(); ++i) {
        error = checkGrain(grains, i, forest);
        if (!error.empty())
            break;
        double const rho = grains.mass[i] * invVolume;
        bool const inside = forEachCell(grains, i, [&](CellOwner const& o, double w) {
            if (o.localBlock >= 0)
                density.block(static_cast<std::size_t>(o.localBlock))[o.pad] += w * rho;
            else
                remote[o.rank][o.row] += w * rho;
        });
        if (!inside)
            error = outside(grains, i, forest, m_layout->spacing());
    }
    agree(error); // before any message: no rank may be left waiting in the exchange

    for (auto const& [rank, cells] : remote) {
        auto& out = m_exchange->sendBuffer(rank);
        std::vector<std::int64_t> rows;
        std::vector<double> values;
        for (auto const& [row, v] : cells) {
            rows.push_back(row);
            values.push_back(v);
        }
        out << rows << values;
    }
    m_exchange->start();
    m_exchange->wait([&](int, core::RecvBuffer& in) {
        std::vector<std::int64_t> rows;
        std::vector<double> values;
        in >> rows >> values;
        if (rows.size() != values.size())
            throw core::Error("MeshTransfer: corrupt deposit message");
        for (std::size_t k = 0; k < rows.size(); ++k) {
            if (rows[k] < m_layout->rowBegin() || rows[k] >= m_layout->rowEnd())
                throw core::Error("MeshTransfer: deposit message for a cell of another rank");
            auto const [b, cell] = m_layout->localOfRow(rows[k]);
            density.block(b)[m_layout->padOfInterior(cell)] += values[k];
        }
    });
}

void MeshTransfer::interpolate(Grains const& grains, CellField const& field,
                               std::span<double> out) {
    auto const& forest = m_layout->forest();
    auto const nc = static_cast<std::size_t>(field.components());
    if (out.size() != grains.position.size() * nc ||
        (!grains.radius.empty() && grains.radius.size() != grains.position.size()))
        throw core::Error("MeshTransfer::interpolate: output size does not match the grains");
    // Pass 1: which remote cells are needed (each requested once).
    std::map<int, std::vector<std::int64_t>> requests;
    std::unordered_map<std::int64_t, std::size_t> slot; // row -> index into `remoteValues`
    std::string error;
    for (std::size_t i = 0; i < grains.position.size() && error.empty(); ++i) {
        error = checkGrain(grains, i, forest);
        if (!error.empty())
            break;
        bool const inside = forEachCell(grains, i, [&](CellOwner const& o, double) {
            if (o.localBlock < 0 && slot.find(o.row) == slot.end()) {
                slot.emplace(o.row, 0);
                requests[o.rank].push_back(o.row);
            }
        });
        if (!inside)
            error = outside(grains, i, forest, m_layout->spacing());
    }
    agree(error);

    // Round 1: requests; round 2: the owners reply with the values in request order.
    for (auto const& [rank, rows] : requests)
        m_exchange->sendBuffer(rank) << rows;
    m_exchange->start();
    auto asked = m_exchange->wait();
    for (auto& m : asked) {
        std::vector<std::int64_t> rows;
        m.buffer >> rows;
        std::vector<double> values;
        values.reserve(rows.size() * nc);
        for (auto row : rows) {
            if (row < m_layout->rowBegin() || row >= m_layout->rowEnd())
                throw core::Error("MeshTransfer: value request for a cell of another rank");
            auto const [b, cell] = m_layout->localOfRow(row);
            for (std::size_t c = 0; c < nc; ++c)
                values.push_back(
                    field.block(b, static_cast<int>(c))[m_layout->padOfInterior(cell)]);
        }
        m_exchange->sendBuffer(m.rank) << values;
    }
    m_exchange->start();
    std::vector<double> remoteValues;
    m_exchange->wait([&](int from, core::RecvBuffer& in) {
        std::vector<double> values;
        in >> values;
        auto const& rows = requests[from];
        if (values.size() != rows.size() * nc)
            throw core::Error("MeshTransfer: reply of the wrong size from rank " +
                              std::to_string(from));
        for (std::size_t k = 0; k < rows.size(); ++k) {
            slot[rows[k]] = remoteValues.size() / nc;
            remoteValues.insert(remoteValues.end(),
                                values.begin() + static_cast<std::ptrdiff_t>(k * nc),
                                values.begin() + static_cast<std::ptrdiff_t>((k + 1) * nc));
        }
    });

    // Pass 2: the weighted sums.
    std::fill(out.begin(), out.end(), 0.0);
    for (std::size_t i = 0; i < grains.position.size(); ++i)
        forEachCell(grains, i, [&](CellOwner const& o, double w) {
            for (std::size_t c = 0; c < nc; ++c) {
                double const v = o.localBlock >= 0
                                     ? field.block(static_cast<std::size_t>(o.localBlock),
                                                   static_cast<int>(c))[o.pad]
                                     : remoteValues[slot.at(o.row) * nc + c];
                out[i * nc + c] += w * v;
            }
        });
}

} // namespace regolith::gravity
