#pragma once
/// Maps C++ arithmetic types to MPI datatypes.
#include <mpi.h>

#include <cstdint>
#include <type_traits>

namespace regolith::core {

template <class T>
MPI_Datatype mpiType() {
    using U = std::remove_cv_t<T>;
    if constexpr (std::is_same_v<U, double>)
        return MPI_DOUBLE;
    else if constexpr (std::is_same_v<U, float>)
        return MPI_FLOAT;
    else if constexpr (std::is_same_v<U, int>)
        return MPI_INT;
    else if constexpr (std::is_same_v<U, unsigned>)
        return MPI_UNSIGNED;
    else if constexpr (std::is_same_v<U, long>)
        return MPI_LONG;
    else if constexpr (std::is_same_v<U, unsigned long>)
        // Open MPI 4.1 compares MPI_UNSIGNED_LONG as signed in MIN/MAX (open-mpi/ompi#10525);
        // the fixed-width type is right.
        return sizeof(unsigned long) == 8 ? MPI_UINT64_T : MPI_UNSIGNED_LONG;
    else if constexpr (std::is_same_v<U, long long>)
        return MPI_LONG_LONG;
    else if constexpr (std::is_same_v<U, unsigned long long>)
        return MPI_UNSIGNED_LONG_LONG;
    else if constexpr (std::is_same_v<U, char>)
        return MPI_CHAR;
    else if constexpr (std::is_same_v<U, std::byte> || std::is_same_v<U, unsigned char>)
        return MPI_BYTE;
    else if constexpr (std::is_same_v<U, bool>)
        return MPI_CXX_BOOL;
    else
        static_assert(sizeof(T) == 0, "no MPI datatype for this type");
}

} // namespace regolith::core
