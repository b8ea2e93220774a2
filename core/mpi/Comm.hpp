#pragma once
/// RAII communicator wrapper. No global communicator: subsystems receive a `Comm const&` and
/// duplicate it (`duplicate()`) so their message tags never collide with anyone else's.
#include "core/mpi/MpiType.hpp"

#include <mpi.h>

#include <span>
#include <string>
#include <vector>

namespace regolith::core {

/// Initialises MPI on construction and finalises it on destruction (once per process).
class MpiEnvironment {
public:
    MpiEnvironment(int& argc, char**& argv);
    ~MpiEnvironment();
    MpiEnvironment(MpiEnvironment const&) = delete;
    MpiEnvironment& operator=(MpiEnvironment const&) = delete;
};

enum class ReduceOp { Sum, Min, Max, LogicalAnd, LogicalOr };
MPI_Op toMpi(ReduceOp op);

/// A communicator. Owning (freed on destruction) when made by `duplicate()`, borrowing when
/// wrapping an existing handle such as MPI_COMM_WORLD.
class Comm {
public:
    /// Borrows `raw`; the caller keeps it alive.
    explicit Comm(MPI_Comm raw = MPI_COMM_WORLD);
    ~Comm();
    Comm(Comm&& other) noexcept;
    Comm& operator=(Comm&& other) noexcept;
    Comm(Comm const&) = delete;
    Comm& operator=(Comm const&) = delete;

    /// A new owning communicator with the same group. Collective.
    [[nodiscard]] Comm duplicate() const;

    [[nodiscard]] int rank() const { return m_rank; }
    [[nodiscard]] int size() const { return m_size; }
    [[nodiscard]] MPI_Comm raw() const { return m_raw; }

    void barrier() const; ///< Collective.

    /// Reduction of one value over all ranks, result on every rank. Collective.
    template <class T>
    [[nodiscard]] T allReduce(T value, ReduceOp op) const {
        T result{};
        check(MPI_Allreduce(&value, &result, 1, mpiType<T>(), toMpi(op), m_raw), "MPI_Allreduce");
        return result;
    }
    /// Element-wise reduction in place, result on every rank. Collective.
    template <class T>
    void allReduceInPlace(std::span<T> values, ReduceOp op) const {
        check(MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()),
                            mpiType<T>(), toMpi(op), m_raw),
              "MPI_Allreduce");
    }
    /// `ok` on every rank? Collective; used to agree on failure before the next collective.
    [[nodiscard]] bool allTrue(bool ok) const {
        return allReduce(static_cast<int>(ok), ReduceOp::Min) != 0;
    }
    /// Gathers one value from every rank on every rank. Collective.
    template <class T>
    [[nodiscard]] std::vector<T> allGather(T value) const {
        std::vector<T> out(static_cast<std::size_t>(m_size));
        check(MPI_Allgather(&value, 1, mpiType<T>(), out.data(), 1, mpiType<T>(), m_raw),
              "MPI_Allgather");
        return out;
    }
    /// Every rank's `mine` (any length) concatenated in rank order, on every rank; `counts`,
    /// if given, receives each rank's length. Collective (MPI_Allgatherv).
    template <class T>
    [[nodiscard]] std::vector<T> allGatherVarying(std::span<T const> mine,
                                                  std::vector<int>* counts = nullptr) const {
        std::vector<int> const n = allGather(static_cast<int>(mine.size()));
        std::vector<int> displs(n.size(), 0);
        int total = 0;
        for (std::size_t r = 0; r < n.size(); ++r) {
            displs[r] = total;
            total += n[r];
        }
        std::vector<T> out(static_cast<std::size_t>(total));
        check(MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), mpiType<T>(), out.data(),
                             n.data(), displs.data(), mpiType<T>(), m_raw),
              "MPI_Allgatherv");
        if (counts != nullptr)
            *counts = n;
        return out;
    }
    /// Gathers a string from every rank on `root` (empty elsewhere). Collective.
    [[nodiscard]] std::vector<std::string> gatherStrings(std::string const& s, int root) const;
    /// Broadcasts a string from `root`. Collective.
    void broadcast(std::string& s, int root) const;

    /// Throws core::Error naming `what` if an MPI call failed.
    static void check(int mpiResult, char const* what);

private:
    MPI_Comm m_raw = MPI_COMM_NULL;
    int m_rank = 0;
    int m_size = 1;
    bool m_owned = false;
};

} // namespace regolith::core
