#pragma once
/// Ghost-layer exchange of cell fields between neighbour blocks, as a plan built once per
/// layout and applied any number of times (Cabana's Halo, waLBerla's HaloExchange):
///  - forward (start()/wait()): every ghost cell that lies in a neighbour block's image
///    (same rank or remote, periodic images included, a block may be its own neighbour)
///    receives a copy of that interior cell;
///  - reverse (startAdd()/waitAdd()): every such ghost cell's value is ADDED to the interior
///    cell it mirrors (deposition into ghost layers).
/// Ghost cells beyond a non-periodic domain face belong to no block and are left alone.
#include "core/mpi/NeighbourExchange.hpp"
#include "gravity/field/CellField.hpp"

#include <array>
#include <memory>
#include <vector>

namespace regolith::gravity {

class GhostExchange {
public:
    /// Builds the plan from the forest's neighbour links; no message is sent per region
    /// list: both sides derive the same sorted list (key: receiving block, sending block,
    /// image). COLLECTIVE over `comm` (sets up a NeighbourExchange with forest.neighbourRanks()).
    /// Pre: `layout` outlives this object.
    GhostExchange(core::Comm const& comm, CellLayout const& layout);
    ~GhostExchange();
    GhostExchange(GhostExchange const&) = delete;
    GhostExchange& operator=(GhostExchange const&) = delete;

    /// Sends this rank's interior cells that neighbours need and copies the rank-local ones
    /// (overlapping the messages); every component of `field`. Pre: no call in flight; field
    /// built on the same layout and not resized until wait(). COLLECTIVE over the neighbour
    /// ranks (every neighbour calls start()/wait() the same number of times).
    void start(CellField& field);
    /// Completes start(): writes the received values into the ghost cells.
    void wait(CellField& field);
    void exchange(CellField& field) {
        start(field);
        wait(field);
    }

    /// Reverse: sends ghost-cell values to their owners and adds the rank-local ones into
    /// their interior cells. Ghost values are left as they are (callers usually zero them
    /// before the next deposition). Same collectivity as start().
    void startAdd(CellField& field);
    /// Completes startAdd(): adds the received values into this rank's interior cells.
    void waitAdd(CellField& field);
    void accumulate(CellField& field) {
        startAdd(field);
        waitAdd(field);
    }

    /// A box of cells of one local block, in block-local cell indices (ghosts negative or
    /// >= n), half-open.
    struct Box {
        int block = -1;
        std::array<int, 3> lo{};
        std::array<int, 3> hi{};
        [[nodiscard]] std::size_t size() const;
    };
    /// Ghost cells filled per call (this rank, all blocks): a check for the tests.
    [[nodiscard]] std::size_t ghostCellsCovered() const;

private:
    struct LocalCopy {
        Box ghost;  ///< destination (ghost cells)
        Box source; ///< interior cells of the same extent
    };
    struct Peer {
        int rank = -1;
        std::vector<Box> send; ///< interior boxes of this rank, in the peer's key order
        std::vector<Box> recv; ///< ghost boxes of this rank, in key order
    };

    CellLayout const* m_layout;
    std::vector<LocalCopy> m_local;
    std::vector<Peer> m_peers;
    std::unique_ptr<core::NeighbourExchange> m_exchange;
    std::vector<double> m_scratch;
};

} // namespace regolith::gravity
