#include "gravity/field/GhostExchange.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace regolith::gravity {

namespace {

using Key = std::tuple<std::uint64_t, std::uint64_t, std::array<int, 3>>;

GlobalCell rootOrigin(CellLayout const& layout, domain::BlockId id) {
    auto const c = layout.forest().geometry().rootCoord(id.rootIndex());
    auto const& n = layout.cellsPerBlock();
    return {c[0] * n[0], c[1] * n[1], c[2] * n[2]};
}

/// The part of receiving block A's padded box (origin oA) that lies in the image of block B
/// whose first cell is at imageOrigin (global cells). Returns false if empty. Boxes relative
/// to A's origin (ghost) and to the image's origin (source).
bool overlap(CellLayout const& layout, GlobalCell const& oA, GlobalCell const& imageOrigin,
             std::array<int, 3>& ghostLo, std::array<int, 3>& ghostHi, std::array<int, 3>& srcLo) {
    auto const& n = layout.cellsPerBlock();
    int const g = layout.ghost();
    for (int a = 0; a < 3; ++a) {
        std::int64_t const lo = std::max(oA[a] - g, imageOrigin[a]);
        std::int64_t const hi = std::min(oA[a] + n[a] + g, imageOrigin[a] + n[a]);
        if (lo >= hi)
            return false;
        ghostLo[a] = static_cast<int>(lo - oA[a]);
        ghostHi[a] = static_cast<int>(hi - oA[a]);
        srcLo[a] = static_cast<int>(lo - imageOrigin[a]);
    }
    return true;
}

GlobalCell imageOrigin(CellLayout const& layout, GlobalCell o, domain::PeriodicImage const& im,
                       int sign) {
    for (int a = 0; a < 3; ++a)
        o[a] += sign * im[a] * layout.globalCells()[a];
    return o;
}

template <class F>
void forEachCell(GhostExchange::Box const& box, F&& f) {
    for (int k = box.lo[2]; k < box.hi[2]; ++k)
        for (int j = box.lo[1]; j < box.hi[1]; ++j)
            for (int i = box.lo[0]; i < box.hi[0]; ++i)
                f(i, j, k);
}

void pack(CellField const& field, std::vector<GhostExchange::Box> const& boxes,
          std::vector<double>& out) {
    out.clear();
    for (auto const& box : boxes)
        for (int c = 0; c < field.components(); ++c)
            forEachCell(box, [&](int i, int j, int k) {
                out.push_back(field.at(static_cast<std::size_t>(box.block), i, j, k, c));
            });
}

template <bool kAdd>
void unpack(CellField& field, std::vector<GhostExchange::Box> const& boxes, core::RecvBuffer& in,
            int from) {
    std::size_t total = 0;
    for (auto const& box : boxes)
        total += box.size() * static_cast<std::size_t>(field.components());
    if (in.remaining() != total * sizeof(double))
        throw core::Error("GhostExchange: message from rank " + std::to_string(from) + " has " +
                          std::to_string(in.remaining()) + " bytes, expected " +
                          std::to_string(total * sizeof(double)));
    std::vector<double> values(total);
    in.readBytes(values.data(), total * sizeof(double), "ghost cells");
    std::size_t v = 0;
    for (auto const& box : boxes)
        for (int c = 0; c < field.components(); ++c)
            forEachCell(box, [&](int i, int j, int k) {
                double& cell = field.at(static_cast<std::size_t>(box.block), i, j, k, c);
                if constexpr (kAdd)
                    cell += values[v++];
                else
                    cell = values[v++];
            });
}

/// Packs every peer's boxes (`boxes`: Peer::send forward, Peer::recv for the reverse add)
/// and starts the exchange.
template <class Peers, class Boxes>
void sendBoxes(CellField const& field, Peers const& peers, Boxes boxes,
               core::NeighbourExchange& exchange, std::vector<double>& scratch) {
    for (auto const& p : peers) {
        pack(field, p.*boxes, scratch);
        exchange.sendBuffer(p.rank).writeBytes(scratch.data(), scratch.size() * sizeof(double));
    }
    exchange.start();
}

/// The same-rank copies: forward (ghost = source) or, for the reverse exchange, adding the
/// ghost cells to their sources.
template <bool kReverseAdd, class Copies>
void copyLocal(CellField& field, Copies const& copies) {
    for (auto const& copy : copies)
        for (int c = 0; c < field.components(); ++c) {
            auto const& g = copy.ghost;
            auto const& s = copy.source;
            forEachCell(g, [&](int i, int j, int k) {
                double& ghost = field.at(static_cast<std::size_t>(g.block), i, j, k, c);
                double& source = field.at(static_cast<std::size_t>(s.block), i - g.lo[0] + s.lo[0],
                                          j - g.lo[1] + s.lo[1], k - g.lo[2] + s.lo[2], c);
                if constexpr (kReverseAdd)
                    source += ghost;
                else
                    ghost = source;
            });
        }
}

void checkField(CellLayout const* layout, CellField const& field) {
    if (&field.layout() != layout)
        throw core::Error("GhostExchange: the field was built on another cell layout");
}

} // namespace

std::size_t GhostExchange::Box::size() const {
    return static_cast<std::size_t>(hi[0] - lo[0]) * static_cast<std::size_t>(hi[1] - lo[1]) *
           static_cast<std::size_t>(hi[2] - lo[2]);
}

GhostExchange::GhostExchange(core::Comm const& comm, CellLayout const& layout)
    : m_layout(&layout) {
    auto const& forest = layout.forest();
    std::map<int, std::vector<std::pair<Key, Box>>> sends;
    std::map<int, std::vector<std::pair<Key, Box>>> recvs;
    auto const blocks = forest.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        auto const& block = blocks[b];
        GlobalCell const oThis = layout.origin(b);
        for (auto const& link : block.neighbours) {
            GlobalCell const oOther = rootOrigin(layout, link.id);
            // Receiving side: this block's ghosts inside the neighbour's image.
            Box ghost{static_cast<int>(b), {}, {}};
            std::array<int, 3> srcLo{};
            if (overlap(layout, oThis, imageOrigin(layout, oOther, link.image, +1), ghost.lo,
                        ghost.hi, srcLo)) {
                if (link.owner == forest.rank()) {
                    auto const* src = forest.findBlock(link.id);
                    Box source{static_cast<int>(src - blocks.data()), srcLo, {}};
                    for (int a = 0; a < 3; ++a)
                        source.hi[a] = srcLo[a] + ghost.hi[a] - ghost.lo[a];
                    m_local.push_back({ghost, source});
                } else {
                    recvs[link.owner].push_back(
                        {Key{block.id.raw(), link.id.raw(), link.image}, ghost});
                }
            }
            if (link.owner == forest.rank())
                continue;
            // Sending side: the neighbour's ghosts inside this block's image as the neighbour
            // sees it (image -link.image, see domain/Block.hpp).
            domain::PeriodicImage const back{-link.image[0], -link.image[1], -link.image[2]};
            std::array<int, 3> lo{};
            std::array<int, 3> hi{};
            GlobalCell const myImage = imageOrigin(layout, oThis, back, +1);
            if (overlap(layout, oOther, myImage, lo, hi, srcLo)) {
                Box source{static_cast<int>(b), srcLo, {}};
                for (int a = 0; a < 3; ++a)
                    source.hi[a] = srcLo[a] + hi[a] - lo[a];
                sends[link.owner].push_back({Key{link.id.raw(), block.id.raw(), back}, source});
            }
        }
    }
    auto byKey = [](auto const& x, auto const& y) { return x.first < y.first; };
    for (int rank : forest.neighbourRanks()) {
        Peer p;
        p.rank = rank;
        auto& s = sends[rank];
        auto& r = recvs[rank];
        std::sort(s.begin(), s.end(), byKey);
        std::sort(r.begin(), r.end(), byKey);
        for (auto& x : s)
            p.send.push_back(x.second);
        for (auto& x : r)
            p.recv.push_back(x.second);
        m_peers.push_back(std::move(p));
    }
    m_exchange = std::make_unique<core::NeighbourExchange>(comm, forest.neighbourRanks());
}

GhostExchange::~GhostExchange() = default;

std::size_t GhostExchange::ghostCellsCovered() const {
    std::size_t n = 0;
    for (auto const& c : m_local)
        n += c.ghost.size();
    for (auto const& p : m_peers)
        for (auto const& b : p.recv)
            n += b.size();
    return n;
}

void GhostExchange::start(CellField& field) {
    checkField(m_layout, field);
    sendBoxes(field, m_peers, &Peer::send, *m_exchange, m_scratch);
    // Local copies while the messages travel: interior cells only are read, ghost cells only
    // written, so the order does not matter.
    copyLocal<false>(field, m_local);
}

void GhostExchange::wait(CellField& field) {
    checkField(m_layout, field);
    std::size_t next = 0;
    m_exchange->wait([&](int from, core::RecvBuffer& in) {
        while (m_peers[next].rank != from)
            ++next;
        unpack<false>(field, m_peers[next].recv, in, from);
    });
}

void GhostExchange::startAdd(CellField& field) {
    checkField(m_layout, field);
    sendBoxes(field, m_peers, &Peer::recv, *m_exchange, m_scratch);
    copyLocal<true>(field, m_local);
}

void GhostExchange::waitAdd(CellField& field) {
    checkField(m_layout, field);
    std::size_t next = 0;
    m_exchange->wait([&](int from, core::RecvBuffer& in) {
        while (m_peers[next].rank != from)
            ++next;
        unpack<true>(field, m_peers[next].send, in, from);
    });
}

} // namespace regolith::gravity
