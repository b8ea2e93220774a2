#pragma once
/// Giving up on point-to-point requests on a failure path, so that an exception never leaves
/// an exchange object still holding an active MPI request.
///
/// Background (MPI-3.1): a receive marked with MPI_Cancel completes locally, "irrespective of
/// the activities of other processes" (§3.8.4), so cancelling and waiting is safe. A send
/// cannot be relied on to cancel (cancelling sends is deprecated in MPI-4.0), but may be
/// freed while active (§3.7.3): it goes on and its request is deallocated when it ends. A
/// nonblocking collective request must not be freed or cancelled (§5.12): completing it is
/// the only legal way out. After an MPI call returned an error, "the state of MPI is
/// undefined" (§8.3), so these are best effort there.
#include <mpi.h>

#include <span>

namespace regolith::core {

/// Cancels every active RECEIVE request in `requests` and completes it (local, cannot hang);
/// a request that then fails to complete is freed instead. Afterwards every handle is
/// MPI_REQUEST_NULL and, unless MPI reported an error, no receive buffer is in use by MPI.
/// Never throws; makes no MPI call once MPI is finalised.
inline void cancelReceives(std::span<MPI_Request> requests) noexcept {
    int finalised = 0;
    MPI_Finalized(&finalised);
    for (MPI_Request& r : requests) {
        if (r != MPI_REQUEST_NULL && !finalised) {
            MPI_Cancel(&r);
            if (MPI_Wait(&r, MPI_STATUS_IGNORE) != MPI_SUCCESS && r != MPI_REQUEST_NULL)
                MPI_Request_free(&r);
        }
        r = MPI_REQUEST_NULL;
    }
}

/// Frees every active SEND request in `requests` without waiting (the send goes on if it can;
/// its buffer must stay untouched until then, which after an MPI error nobody can promise)
/// and sets each handle to MPI_REQUEST_NULL. Never throws; no MPI call once MPI is finalised.
inline void releaseSends(std::span<MPI_Request> requests) noexcept {
    int finalised = 0;
    MPI_Finalized(&finalised);
    for (MPI_Request& r : requests) {
        if (r != MPI_REQUEST_NULL && !finalised)
            MPI_Request_free(&r);
        r = MPI_REQUEST_NULL;
    }
}

} // namespace regolith::core
