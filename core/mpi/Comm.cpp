#include "core/mpi/Comm.hpp"

#include "core/Error.hpp"
#include "core/memory/MemoryBudget.hpp"

#include <utility>

namespace regolith::core {

MpiEnvironment::MpiEnvironment(int& argc, char**& argv) {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
        int provided = 0;
        Comm::check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided),
                    "MPI_Init_thread");
    }
    // Errors come back as codes that Comm::check turns into exceptions.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    agreeOnPhysicalMemory();
}

MpiEnvironment::~MpiEnvironment() {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised)
        MPI_Finalize();
}

MPI_Op toMpi(ReduceOp op) {
    switch (op) {
    case ReduceOp::Sum:
        return MPI_SUM;
    case ReduceOp::Min:
        return MPI_MIN;
    case ReduceOp::Max:
        return MPI_MAX;
    case ReduceOp::LogicalAnd:
        return MPI_LAND;
    case ReduceOp::LogicalOr:
        return MPI_LOR;
    }
    return MPI_OP_NULL;
}

Comm::Comm(MPI_Comm raw)
    : m_raw(raw) {
    check(MPI_Comm_rank(m_raw, &m_rank), "MPI_Comm_rank");
    check(MPI_Comm_size(m_raw, &m_size), "MPI_Comm_size");
}

Comm::~Comm() {
    if (m_owned && m_raw != MPI_COMM_NULL) {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (!finalised)
            MPI_Comm_free(&m_raw);
    }
}

Comm::Comm(Comm&& other) noexcept
    : m_raw(std::exchange(other.m_raw, MPI_COMM_NULL))
    , m_rank(other.m_rank)
    , m_size(other.m_size)
    , m_owned(std::exchange(other.m_owned, false)) {}

Comm& Comm::operator=(Comm&& other) noexcept {
    if (this != &other) {
        Comm tmp(std::move(*this));
        m_raw = std::exchange(other.m_raw, MPI_COMM_NULL);
        m_rank = other.m_rank;
        m_size = other.m_size;
        m_owned = std::exchange(other.m_owned, false);
    }
    return *this;
}

Comm Comm::duplicate() const {
    MPI_Comm dup = MPI_COMM_NULL;
    check(MPI_Comm_dup(m_raw, &dup), "MPI_Comm_dup");
    MPI_Comm_set_errhandler(dup, MPI_ERRORS_RETURN);
    Comm out(dup);
    out.m_owned = true;
    return out;
}

void Comm::barrier() const {
    check(MPI_Barrier(m_raw), "MPI_Barrier");
}

std::vector<std::string> Comm::gatherStrings(std::string const& s, int root) const {
    int const len = static_cast<int>(s.size());
    std::vector<int> lens(m_rank == root ? static_cast<std::size_t>(m_size) : 0);
    check(MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, root, m_raw), "MPI_Gather");
    std::vector<int> displs(lens.size(), 0);
    int total = 0;
    for (std::size_t i = 0; i < lens.size(); ++i) {
        displs[i] = total;
        total += lens[i];
    }
    std::string all(static_cast<std::size_t>(total), '\0');
    check(MPI_Gatherv(s.data(), len, MPI_CHAR, all.data(), lens.data(), displs.data(), MPI_CHAR,
                      root, m_raw),
          "MPI_Gatherv");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < lens.size(); ++i)
        out.push_back(
            all.substr(static_cast<std::size_t>(displs[i]), static_cast<std::size_t>(lens[i])));
    return out;
}

void Comm::broadcast(std::string& s, int root) const {
    auto len = static_cast<unsigned long>(s.size());
    check(MPI_Bcast(&len, 1, MPI_UNSIGNED_LONG, root, m_raw), "MPI_Bcast");
    s.resize(len);
    check(MPI_Bcast(s.data(), static_cast<int>(len), MPI_CHAR, root, m_raw), "MPI_Bcast");
}

void Comm::check(int mpiResult, char const* what) {
    if (mpiResult == MPI_SUCCESS)
        return;
    char text[MPI_MAX_ERROR_STRING];
    int len = 0;
    MPI_Error_string(mpiResult, text, &len);
    throw Error(std::string(what) + " failed: " + std::string(text, static_cast<std::size_t>(len)));
}

} // namespace regolith::core
