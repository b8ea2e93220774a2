#include "core/mpi/AgreeOnInputError.hpp"

#include "core/Error.hpp"

#include <string>

namespace regolith::core {

void agreeOnInputError(core::Comm const& comm, std::function<void()> const& action) {
    std::string failure;
    bool failed = false;
    try {
        action();
    } catch (core::InputError const& e) {
        failed = true;
        failure = e.what();
        if (failure.empty())
            failure = "unknown input error";
    }
    // One reduction does both the agreement (any failure?) and the choice of the reporter:
    // the smallest failing rank, or size() when every rank succeeded.
    int const reporter = comm.allReduce(failed ? comm.rank() : comm.size(), core::ReduceOp::Min);
    if (reporter == comm.size())
        return;
    comm.broadcast(failure, reporter);
    throw core::InputError(failure);
}

} // namespace regolith::core
