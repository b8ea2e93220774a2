#pragma once
/// Hierarchical phase timers: nested RAII scopes build a tree of phases ("step/sync/exchange")
/// accumulating seconds and call counts per node, reduced over ranks to min/avg/max.
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerReport.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::core {

/// A tree of timed phases on one rank.
///
///     TimerTree timers;
///     {
///         auto step = timers.scope("step");
///         { auto t = timers.scope("sync"); ... }      // node "step/sync"
///     }
///     TimerReport r = timers.reduce(comm);             // collective
///
/// A scope opens a child of the innermost open scope (or a top-level phase); re-entering a
/// phase under the same parent accumulates into the same node. Times are inclusive (a node's
/// time contains its children's). Not thread-safe: one tree per thread.
class TimerTree {
public:
    /// Returns the current time in seconds; only differences are used. Must not go backwards.
    using Clock = std::function<double()>;

    /// An open phase; adds its duration and one call to its node when it ends. Neither copyable
    /// nor movable (`auto t = timers.scope(..)` works by guaranteed copy elision), so scopes
    /// end in reverse order of opening unless stop() is misused, which throws.
    class Scope {
    public:
        ~Scope();
        Scope(Scope const&) = delete;
        Scope& operator=(Scope const&) = delete;
        Scope(Scope&&) = delete;
        Scope& operator=(Scope&&) = delete;

        /// Ends the phase early (the destructor then does nothing). Throws core::Error if this
        /// is not the innermost open scope; does nothing if already stopped.
        void stop();

    private:
        friend class TimerTree;
        Scope(TimerTree& tree, std::size_t node, double start)
            : m_tree(&tree)
            , m_node(node)
            , m_start(start) {}

        TimerTree* m_tree;
        std::size_t m_node;
        double m_start;
        bool m_open = true;
    };

    /// Times with std::chrono::steady_clock.
    TimerTree();
    /// Times with `clock`, e.g. `[] { return MPI_Wtime(); }` or a fake clock in tests.
    explicit TimerTree(Clock clock);

    /// Opens phase `name` under the innermost open scope. Pre: `name` is non-empty and has no
    /// '/' or newline (throws core::Error otherwise).
    [[nodiscard]] Scope scope(std::string_view name);

    /// Adds `seconds` and `calls` to the node at absolute `path` ("step/sync"), creating it and
    /// its ancestors as needed. For durations measured elsewhere, and a test hook that lets a
    /// test inject exact durations instead of sleeping. Throws core::Error on a malformed path
    /// or negative seconds.
    void addTime(std::string_view path, double seconds, std::uint64_t calls = 1);

    /// Accumulated seconds at `path`; 0 if there is no such node.
    [[nodiscard]] double seconds(std::string_view path) const;
    /// Accumulated calls at `path`; 0 if there is no such node.
    [[nodiscard]] std::uint64_t calls(std::string_view path) const;
    /// Whether `path` has a node.
    [[nodiscard]] bool contains(std::string_view path) const;
    /// All node paths in pre-order (a phase before its sub-phases, siblings in creation order).
    [[nodiscard]] std::vector<std::string> paths() const;
    /// Path of the innermost open scope ("" if none).
    [[nodiscard]] std::string currentPath() const;

    /// Forgets all nodes (e.g. after set-up). Throws core::Error while a scope is open.
    void reset();

    /// Min/avg/max of every phase over the ranks of `comm`; ranks may have different trees
    /// (union of paths, a missing phase counts as 0). Open scopes are not included. The same
    /// report is returned on every rank. COLLECTIVE over `comm`.
    [[nodiscard]] TimerReport reduce(Comm const& comm) const;

private:
    struct Node {
        std::string name;
        std::size_t parent = 0;
        std::vector<std::size_t> children;
        double seconds = 0.0;
        std::uint64_t calls = 0;
    };
    static constexpr std::size_t kRoot = 0;

    /// Child `name` of `parent`, created if absent.
    std::size_t child(std::size_t parent, std::string_view name);
    /// Node at `path`, created with its ancestors if absent; throws on a malformed path.
    std::size_t findOrCreate(std::string_view path);
    /// Node at `path`, or SIZE_MAX if absent.
    [[nodiscard]] std::size_t find(std::string_view path) const;
    [[nodiscard]] std::string pathOf(std::size_t node) const;
    void preorder(std::size_t node, std::vector<std::size_t>& out) const;
    void close(std::size_t node, double start);

    Clock m_clock;
    std::vector<Node> m_nodes;
    std::vector<std::size_t> m_open; ///< stack of open scopes' nodes
};

} // namespace regolith::core
